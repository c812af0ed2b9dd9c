#include "mcxRTKGeometryFile.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkXMLParser.h"
#include "vtksys/SystemTools.hxx"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace mcxio
{

namespace
{
// A geometry file of the most projections mcxray renders takes a few tens
// of MiB; a larger one is no geometry file.
const std::size_t MaximumFileBytes = std::size_t(256) << 20;
// The longest text of one element: a Matrix of 12 numbers in RTK's layout
// takes about 300 characters.
const std::size_t MaximumText = 4096;

bool Is(const char* name, const char* expected)
{
  return vtksys::SystemTools::Strucmp(name, expected) == 0;
}

// Whitespace-separated numbers, each whole and finite; false if the text
// holds another count or anything else.
bool ParseNumbers(const std::string& text, std::size_t count, double* out)
{
  const char* p = text.c_str();
  for (std::size_t k = 0; k <= count; ++k)
  {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
    {
      ++p;
    }
    if (k == count)
    {
      return *p == '\0';
    }
    char* end = nullptr;
    errno = 0;
    out[k] = std::strtod(p, &end);
    if (end == p || errno == ERANGE || !std::isfinite(out[k]) ||
      (*end != '\0' && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r'))
    {
      return false;
    }
    p = end;
  }
  return false;
}

class RTKGeometryParser : public vtkXMLParser
{
public:
  static RTKGeometryParser* New();
  vtkTypeMacro(RTKGeometryParser, vtkXMLParser);

  std::size_t Limit = 0;
  std::vector<RTKGeometryProjection>* Projections = nullptr;
  std::string Error;
  bool RootSeen = false;
  bool SourceToIsocenterGiven = false;
  bool SourceToDetectorGiven = false;

protected:
  RTKGeometryParser() = default;

  void StartElement(const char* name, const char** attributes) override
  {
    this->Text.clear();
    if (!this->Error.empty())
    {
      return;
    }
    if (!this->RootSeen)
    {
      this->RootSeen = true;
      if (!Is(name, "RTKThreeDCircularGeometry"))
      {
        this->Fail(std::string("the root element is <") + name +
          ">, not <RTKThreeDCircularGeometry>: no RTK circular geometry");
        return;
      }
      std::string version;
      for (const char** a = attributes; a && a[0] && a[1]; a += 2)
      {
        if (std::string(a[0]) == "version")
        {
          version = a[1];
        }
      }
      if (version != "2" && version != "3")
      {
        this->Fail(
          "RTKThreeDCircularGeometry version '" + version + "' (RTK reads versions 2 and 3)");
      }
    }
  }

  void EndElement(const char* name) override
  {
    if (!this->Error.empty())
    {
      return;
    }
    mcx::RTKProjection& p = this->Current.Parameters;
    struct Field
    {
      const char* Name;
      double* Value;
    };
    const Field fields[] = { { "SourceToIsocenterDistance", &p.SourceToIsocenterDistance },
      { "SourceToDetectorDistance", &p.SourceToDetectorDistance },
      { "GantryAngle", &p.GantryAngle }, { "Angle", &p.GantryAngle }, // RTK's old name
      { "ProjectionOffsetX", &p.ProjectionOffsetX }, { "ProjectionOffsetY", &p.ProjectionOffsetY },
      { "OutOfPlaneAngle", &p.OutOfPlaneAngle }, { "InPlaneAngle", &p.InPlaneAngle },
      { "SourceOffsetX", &p.SourceOffsetX }, { "SourceOffsetY", &p.SourceOffsetY } };
    for (const Field& field : fields)
    {
      if (Is(name, field.Name))
      {
        if (!ParseNumbers(this->Text, 1, field.Value))
        {
          this->Fail(
            std::string("<") + name + "> holds '" + this->Shown() + "', not a finite number");
        }
        this->SourceToIsocenterGiven |= field.Value == &p.SourceToIsocenterDistance;
        this->SourceToDetectorGiven |= field.Value == &p.SourceToDetectorDistance;
        return;
      }
    }
    if (Is(name, "RadiusCylindricalDetector"))
    {
      double radius = 0;
      if (!ParseNumbers(this->Text, 1, &radius) || radius != 0)
      {
        this->Fail("RadiusCylindricalDetector '" + this->Shown() +
          "': only flat detectors (0) are rendered");
      }
    }
    else if (Is(name, "Matrix"))
    {
      if (!ParseNumbers(this->Text, 12, this->Current.Matrix))
      {
        this->Fail("<Matrix> must hold 12 finite numbers, not '" + this->Shown() + "'");
      }
      this->Current.HasMatrix = true;
    }
    else if (Is(name, "Projection"))
    {
      if (!this->SourceToIsocenterGiven || !this->SourceToDetectorGiven)
      {
        this->Fail("projection " + std::to_string(this->Projections->size()) + " has no " +
          (this->SourceToIsocenterGiven ? "SourceToDetectorDistance"
                                        : "SourceToIsocenterDistance"));
        return;
      }
      if (this->Projections->size() >= this->Limit)
      {
        this->Fail("more than " + std::to_string(this->Limit) + " projections");
        return;
      }
      this->Projections->push_back(this->Current);
      this->Current.HasMatrix = false; // a matrix is its projection's alone
    }
  }

  void CharacterDataHandler(const char* data, int length) override
  {
    if (this->Text.size() + static_cast<std::size_t>(length) > MaximumText)
    {
      this->Fail("an element holds more than " + std::to_string(MaximumText) + " characters");
      return;
    }
    this->Text.append(data, static_cast<std::size_t>(length));
  }

  void ReportXmlParseError() override
  {
    if (this->Error.empty())
    {
      this->Error = "not well-formed XML";
    }
  }

private:
  void Fail(const std::string& why)
  {
    if (this->Error.empty())
    {
      this->Error = why;
    }
  }

  // The text as a message quotes it: trimmed, at most 40 bytes (mcxray's
  // error line escapes what is not printable).
  std::string Shown() const
  {
    const std::size_t first = this->Text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
    {
      return std::string();
    }
    const std::size_t last = this->Text.find_last_not_of(" \t\r\n");
    std::string shown = this->Text.substr(first, last - first + 1);
    return shown.size() > 40 ? shown.substr(0, 40) + "..." : shown;
  }

  RTKGeometryProjection Current;
  std::string Text;
};
vtkStandardNewMacro(RTKGeometryParser);
}

std::string ReadRTKGeometry(
  const std::string& path, std::size_t limit, std::vector<RTKGeometryProjection>& projections)
{
  const std::string named = "RTK geometry '" + path + "': ";
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return named + "no such file";
  }
  if (vtksys::SystemTools::FileLength(path) > MaximumFileBytes)
  {
    return named + "larger than " + std::to_string(MaximumFileBytes >> 20) +
      " MiB: no geometry file";
  }
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    return named + "cannot be opened";
  }
  vtkNew<RTKGeometryParser> parser;
  parser->Limit = limit;
  parser->Projections = &projections;
  projections.clear();
  parser->InitializeParser();
  char buffer[65536];
  while (parser->Error.empty() && file)
  {
    file.read(buffer, sizeof(buffer));
    if (file.gcount() > 0)
    {
      parser->ParseChunk(buffer, static_cast<unsigned int>(file.gcount()));
    }
  }
  parser->CleanupParser(); // frees expat's parser; reports an unfinished document
  if (parser->Error.empty() && projections.empty())
  {
    parser->Error = "no <Projection>";
  }
  if (!parser->Error.empty())
  {
    projections.clear();
    return named + parser->Error;
  }
  return std::string();
}

} // namespace mcxio
