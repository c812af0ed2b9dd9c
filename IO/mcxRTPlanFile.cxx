#include "mcxRTPlanFile.h"

#include "mcxDicomFiles.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMItem.h"
#include "vtkDICOMMetaData.h"
#include "vtkDICOMParser.h"
#include "vtkDICOMValue.h"
#include "vtkNew.h"
#include "vtksys/SystemTools.hxx"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace mcxio
{

namespace
{
const char* const RTPlanClass = "1.2.840.10008.5.1.4.1.1.481.5";
// A plan of thousands of control points takes a few MiB.
const unsigned long MaximumFileBytes = 64ul << 20;

std::string Trimmed(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
  {
    return std::string();
  }
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

// The text as a message quotes it: trimmed, at most 40 bytes (mcxray's
// error line escapes what is not printable).
std::string Shown(const std::string& text)
{
  std::string shown = Trimmed(text);
  return shown.size() > 40 ? shown.substr(0, 40) + "..." : shown;
}

// Component k of a decimal string (DS) or float (FL) attribute, strictly: a
// whole finite number.
bool Number(const vtkDICOMValue& value, std::size_t k, double& out)
{
  if (!value.IsValid() || k >= value.GetNumberOfValues())
  {
    return false;
  }
  if (value.GetVR() == vtkDICOMVR::FL || value.GetVR() == vtkDICOMVR::FD)
  {
    out = value.GetDouble(k);
    return std::isfinite(out);
  }
  const std::string text = Trimmed(value.GetString(k));
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && errno != ERANGE && std::isfinite(out);
}

// An angle of the first control point, in [0, 360) as DICOM states.
std::string Angle(const vtkDICOMItem& point, vtkDICOMTag tag, const char* name, double& out)
{
  const vtkDICOMValue& value = point.Get(tag);
  if (!value.IsValid())
  {
    return std::string("its first control point has no ") + name;
  }
  if (!Number(value, 0, out) || !(out >= 0 && out < 360))
  {
    return std::string(name) + " '" + Shown(value.AsString()) + "' is no angle in [0, 360) degrees";
  }
  return std::string();
}

// The patient position of the beam's setup: its ReferencedPatientSetupNumber
// in PatientSetupSequence, or the plan's only setup.
std::string PatientPosition(vtkDICOMMetaData* meta, const vtkDICOMItem& beam, std::string& position)
{
  const vtkDICOMValue& setups = meta->Get(DC::PatientSetupSequence);
  const std::size_t count = setups.IsValid() ? setups.GetNumberOfValues() : 0;
  const vtkDICOMItem* items = count ? setups.GetSequenceData() : nullptr;
  if (!items)
  {
    return "the plan has no PatientSetupSequence: the patient's position is unknown";
  }
  const vtkDICOMValue& referenced = beam.Get(DC::ReferencedPatientSetupNumber);
  const vtkDICOMItem* setup = nullptr;
  if (referenced.IsValid())
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      if (items[k].Get(DC::PatientSetupNumber).AsInt() == referenced.AsInt())
      {
        setup = &items[k];
      }
    }
    if (!setup)
    {
      return "the beam's ReferencedPatientSetupNumber " + Shown(referenced.AsString()) +
        " is not in PatientSetupSequence";
    }
  }
  else if (count == 1)
  {
    setup = &items[0];
  }
  else
  {
    return "the beam names no ReferencedPatientSetupNumber among the plan's " +
      std::to_string(count) + " patient setups";
  }
  position = Trimmed(setup->Get(DC::PatientPosition).AsString());
  return std::string();
}

// The beam's geometry (the beam found, its number and name set).
std::string ReadBeam(vtkDICOMMetaData* meta, const vtkDICOMItem& beam, RTPlanBeam& out)
{
  std::string position;
  std::string problem = PatientPosition(meta, beam, position);
  if (!problem.empty())
  {
    return problem;
  }
  if (position != "HFS")
  {
    return "PatientPosition '" + Shown(position) +
      "': only head first supine (HFS) patients are rendered";
  }
  const vtkDICOMValue& sad = beam.Get(DC::SourceAxisDistance);
  out.HasSourceAxisDistance = sad.IsValid();
  if (sad.IsValid() && (!Number(sad, 0, out.SourceAxisDistance) || !(out.SourceAxisDistance > 0)))
  {
    return "SourceAxisDistance '" + Shown(sad.AsString()) + "' is no positive distance";
  }
  const vtkDICOMValue& points = beam.Get(DC::ControlPointSequence);
  const vtkDICOMItem* first =
    points.IsValid() && points.GetNumberOfValues() ? points.GetSequenceData() : nullptr;
  if (!first)
  {
    return "the beam has no ControlPointSequence";
  }
  const vtkDICOMItem& point = first[0];
  for (const std::string& why : { Angle(point, DC::GantryAngle, "GantryAngle", out.GantryAngle),
         Angle(point, DC::BeamLimitingDeviceAngle, "BeamLimitingDeviceAngle",
           out.BeamLimitingDeviceAngle),
         Angle(point, DC::PatientSupportAngle, "PatientSupportAngle", out.PatientSupportAngle) })
  {
    if (!why.empty())
    {
      return why;
    }
  }
  // The table top's own turns move the patient off the IEC couch's axes:
  // refused rather than ignored.
  const struct
  {
    vtkDICOMTag Tag;
    const char* Name;
  } tableTop[] = { { DC::TableTopEccentricAngle, "TableTopEccentricAngle" },
    { DC::TableTopPitchAngle, "TableTopPitchAngle" },
    { DC::TableTopRollAngle, "TableTopRollAngle" } };
  for (const auto& angle : tableTop)
  {
    const vtkDICOMValue& value = point.Get(angle.Tag);
    double degrees = 0;
    if (value.IsValid() && value.GetNumberOfValues() &&
      (!Number(value, 0, degrees) || (degrees != 0 && degrees != 360)))
    {
      return std::string(angle.Name) + " '" + Shown(value.AsString()) +
        "': only 0 is rendered (a table top turned off the couch's axis)";
    }
  }
  const vtkDICOMValue& isocenter = point.Get(DC::IsocenterPosition);
  if (!isocenter.IsValid())
  {
    return "its first control point has no IsocenterPosition";
  }
  if (isocenter.GetNumberOfValues() != 3 || !Number(isocenter, 0, out.IsocenterPosition[0]) ||
    !Number(isocenter, 1, out.IsocenterPosition[1]) ||
    !Number(isocenter, 2, out.IsocenterPosition[2]))
  {
    return "IsocenterPosition '" + Shown(isocenter.AsString()) + "' is not 3 finite numbers";
  }
  return std::string();
}

// The beam of the plan read in this process (ReadRTPlanBeam's work).
std::string ReadBeamHere(const std::string& path, const std::string& beam, RTPlanBeam& out)
{
  const std::string named = "RT plan '" + path + "': ";
  vtkNew<vtkDICOMMetaData> meta;
  vtkNew<vtkDICOMParser> parser;
  vtkNew<vtkCallbackCommand> quiet; // the failure is said once, below
  parser->AddObserver(vtkCommand::ErrorEvent, quiet);
  parser->SetMetaData(meta);
  parser->SetFileName(path.c_str());
  parser->Update();
  if (parser->GetErrorCode())
  {
    return named + "not a DICOM file vtk-dicom can read";
  }
  const std::string sopClass = Trimmed(meta->Get(DC::SOPClassUID).AsString());
  if (sopClass != RTPlanClass)
  {
    return named + "SOPClassUID '" + Shown(sopClass) + "' is no RT Plan (" + RTPlanClass + ")";
  }
  const vtkDICOMValue& beams = meta->Get(DC::BeamSequence);
  const std::size_t count = beams.IsValid() ? beams.GetNumberOfValues() : 0;
  const vtkDICOMItem* items = count ? beams.GetSequenceData() : nullptr;
  if (!items)
  {
    return named + "no BeamSequence";
  }
  std::string listed;
  const vtkDICOMItem* chosen = nullptr;
  for (int pass = 0; pass < 2 && !chosen; ++pass)
  {
    for (std::size_t k = 0; k < count && !chosen; ++k)
    {
      const std::string number = Trimmed(items[k].Get(DC::BeamNumber).AsString());
      const std::string name = Trimmed(items[k].Get(DC::BeamName).AsString());
      if (pass == 0)
      {
        listed += (k ? ", " : "") + Shown(number) + (name.empty() ? "" : " '" + Shown(name) + "'");
      }
      if ((pass == 0 && !beam.empty() && number == beam) ||
        (pass == 1 && !beam.empty() && name == beam) || (beam.empty() && count == 1))
      {
        chosen = &items[k];
        out.Number = items[k].Get(DC::BeamNumber).AsInt();
        out.Name = name;
      }
    }
  }
  if (!chosen)
  {
    return named +
      (beam.empty() ? std::string("choose one of its beams with --beam: ")
                    : "no beam numbered or named '" + Shown(beam) + "' (its beams: ") +
      listed + (beam.empty() ? "" : ")");
  }
  const std::string problem = ReadBeam(meta, *chosen, out);
  return problem.empty() ? problem : named + "beam " + std::to_string(out.Number) + ": " + problem;
}

// What the child hands back: 'E' and the error, or 'B', the beam's numbers
// as this machine stores them, and its name.
template <typename T>
void Put(std::string& bytes, const T& value)
{
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
}

template <typename T>
void Take(const std::string& bytes, std::size_t& at, T& value)
{
  std::memcpy(&value, bytes.data() + at, sizeof(value));
  at += sizeof(value);
}

const std::size_t BeamBytes = sizeof(int) + 7 * sizeof(double) + sizeof(bool);

std::string HandedBack(const std::string& problem, const RTPlanBeam& beam)
{
  if (!problem.empty())
  {
    return "E" + problem;
  }
  std::string bytes = "B";
  Put(bytes, beam.Number);
  Put(bytes, beam.GantryAngle);
  Put(bytes, beam.BeamLimitingDeviceAngle);
  Put(bytes, beam.PatientSupportAngle);
  Put(bytes, beam.HasSourceAxisDistance);
  Put(bytes, beam.SourceAxisDistance);
  for (double x : beam.IsocenterPosition)
  {
    Put(bytes, x);
  }
  return bytes + beam.Name;
}

// The child's answer as ReadRTPlanBeam returns it (named: the plan, as
// errors name it).
std::string TakenBack(const std::string& answer, const std::string& named, RTPlanBeam& beam)
{
  if (answer.size() > 1 && answer[0] == 'E')
  {
    return answer.substr(1);
  }
  if (answer.size() < 1 + BeamBytes || answer[0] != 'B')
  {
    return named + "its reading ended without an answer";
  }
  std::size_t at = 1;
  Take(answer, at, beam.Number);
  Take(answer, at, beam.GantryAngle);
  Take(answer, at, beam.BeamLimitingDeviceAngle);
  Take(answer, at, beam.PatientSupportAngle);
  Take(answer, at, beam.HasSourceAxisDistance);
  Take(answer, at, beam.SourceAxisDistance);
  for (double& x : beam.IsocenterPosition)
  {
    Take(answer, at, x);
  }
  beam.Name = answer.substr(at);
  return std::string();
}
}

std::string ReadRTPlanBeam(const std::string& path, const std::string& beam, RTPlanBeam& out)
{
  const std::string named = "RT plan '" + path + "': ";
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return named + "no such file";
  }
  if (vtksys::SystemTools::FileLength(path) > MaximumFileBytes)
  {
    return named + "larger than 64 MiB: no plan";
  }
  // Parsed in a child (mcxDicomFiles.h: vtk-dicom's parser may read past
  // its buffer): a file that crashes it ends the child, not the caller.
  std::string answer;
  std::string crashed;
  if (!ParseInChild(
        [&]()
        {
          RTPlanBeam read;
          const std::string problem = ReadBeamHere(path, beam, read);
          return HandedBack(problem, read);
        },
        "the plan", answer, crashed))
  {
    return named + crashed;
  }
  return TakenBack(answer, named, out);
}

} // namespace mcxio
