// The values of command-line options: numbers, sizes and triples, each
// checked as it is read; a bad value ends the run with a one-line error
// that names the option.
#ifndef mcxOptionValues_h
#define mcxOptionValues_h

#include <climits>
#include <string>
#include <vector>

namespace mcxapp
{

/// A finite number.
double ParseNumber(const std::string& text, const std::string& option);

/// A number > 0 (else "OPTION must be positive").
double ParsePositive(const std::string& text, const std::string& option);

/// A number in (0, 1) (else "OPTION must lie in (0, 1)").
double ParseOpenUnitFraction(const std::string& text, const std::string& option);

/// A decimal integer in [minimum, maximum]: out of range (including what a
/// long long cannot hold) is an error, never wrapped or clamped.
long long ParseInteger(const std::string& text, const std::string& option, long long minimum,
  long long maximum = LLONG_MAX);

/// A byte count: a positive number with an optional binary suffix K, M, G
/// or T ("512M", "8G"), at most 2^60.
double ParseByteSize(const std::string& text, const std::string& option);

/// "WxH" with each side in [smallest, largest]; `option` names it in errors.
void ParseSize(
  const std::string& text, const std::string& option, int smallest, int largest, int size[2]);

/// "x,y,z"; `what` names the triple in errors (e.g. "--camera position").
void ParseTriple(const std::string& text, double out[3], const std::string& what);

/// Exactly `count` numbers separated by commas or white space (plastimatch
/// writes "x y z"); `what` names them in errors.
std::vector<double> ParseNumberList(
  const std::string& text, std::size_t count, const std::string& what);

/// The parts of text between separators.
std::vector<std::string> Split(const std::string& text, char separator);

} // namespace mcxapp

#endif
