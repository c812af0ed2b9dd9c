// The fuzz targets' Fail: throws the message instead of exiting, so that
// libFuzzer can go on to the next input; the message Fail hands over must
// be one line, whatever the input quoted.
#ifndef FuzzFailThrows_h
#define FuzzFailThrows_h

#include "mcxFail.h"

#include <string>

namespace mcxfuzz
{

struct Refusal
{
  std::string Message;
};

inline void Throw(const std::string& message)
{
  if (message.empty() || message.find('\n') != std::string::npos)
  {
    __builtin_trap();
  }
  throw Refusal{ message };
}

inline void ThrowOnFail()
{
  mcxapp::SetFailHandler(&Throw);
}

} // namespace mcxfuzz

#endif
