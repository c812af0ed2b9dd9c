#include "mcxPoseOutput.h"

#include "mcxFail.h"
#include "mcxImageOutput.h"
#include "mcxProjectionMatrix.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXTypes.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mcxapp
{

namespace
{
std::string Extension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return std::string();
  }
  return path.substr(dot);
}

void WriteRow(std::ostream& out, const double* values, int count)
{
  out << "[";
  for (int k = 0; k < count; ++k)
  {
    out << (k ? ", " : "") << values[k];
  }
  out << "]";
}

void WriteMatrix(std::ostream& out, const double* values, int rows, int columns)
{
  out << "[";
  for (int r = 0; r < rows; ++r)
  {
    out << (r ? ", " : "");
    WriteRow(out, values + r * columns, columns);
  }
  out << "]";
}

void WritePose(std::ostream& out, const PoseRecord& pose)
{
  const double* P = pose.Matrix;
  out << "    {\"size\": [" << pose.Size[0] << ", " << pose.Size[1] << "], \"pixel_spacing\": ";
  WriteRow(out, pose.Spacing, 2);
  out << ",\n     \"P\": ";
  WriteMatrix(out, P, 3, 4);
  mcx::PinholeCamera camera;
  if (P[8] == 0 && P[9] == 0 && P[10] == 0)
  {
    out << ", \"parallel\": true}";
    return;
  }
  if (mcx::PinholeFromMatrix(P, camera).empty())
  {
    const double K[9] = { camera.Fx, 0, camera.Cx, 0, camera.Fy, camera.Cy, 0, 0, 1 };
    double source[3];
    camera.Source(source);
    out << ",\n     \"K\": ";
    WriteMatrix(out, K, 3, 3);
    out << ",\n     \"R\": ";
    WriteMatrix(out, camera.R, 3, 3);
    out << ", \"t\": ";
    WriteRow(out, camera.T, 3);
    out << ", \"source\": ";
    WriteRow(out, source, 3);
  }
  out << "}";
}
}

bool WritesStack(const std::string& path)
{
  return Extension(path) == ".vti" || Extension(path) == ".mha";
}

std::string NumberedOutput(const std::string& path, int index)
{
  const std::string extension = Extension(path);
  char number[16];
  std::snprintf(number, sizeof(number), "_%04d", index);
  return path.substr(0, path.size() - extension.size()) + number + extension;
}

PoseRecord RecordOf(vtkImageData* image)
{
  PoseRecord pose;
  int dims[3];
  image->GetDimensions(dims);
  pose.Size[0] = dims[0];
  pose.Size[1] = dims[1];
  pose.Spacing[0] = image->GetSpacing()[0];
  pose.Spacing[1] = image->GetSpacing()[1];
  image->GetFieldData()->GetArray(vtkMCXTypes::ProjectionMatrixName())->GetTuple(0, pose.Matrix);
  return pose;
}

namespace
{
// An array of from's type, name and components, of `tuples` tuples.
vtkSmartPointer<vtkDataArray> EmptyLike(vtkDataArray* from, vtkIdType tuples)
{
  vtkSmartPointer<vtkDataArray> values = vtk::TakeSmartPointer(from->NewInstance());
  values->SetName(from->GetName());
  values->SetNumberOfComponents(from->GetNumberOfComponents());
  values->SetNumberOfTuples(tuples);
  return values;
}
}

PoseStack::PoseStack(int count, const int size[2], const std::string& path)
  : Count(count)
  , EveryArray(Extension(path) == ".vti")
{
  const double bytes = static_cast<double>(size[0]) * size[1] * count * sizeof(double);
  const std::string problem = mcx::MemoryProblem(bytes,
    "A stack of " + std::to_string(count) + " images of " + std::to_string(size[0]) + " x " +
      std::to_string(size[1]) + " pixels");
  if (!problem.empty())
  {
    Fail(problem + " (write numbered .png or .pfm files instead)");
  }
  this->Image = vtkSmartPointer<vtkImageData>::New();
  this->Image->SetExtent(0, size[0] - 1, 0, size[1] - 1, 0, count - 1);
}

vtkImageData* PoseStack::GetImage() const
{
  return this->Image;
}

void PoseStack::Add(int k, vtkImageData* image)
{
  vtkImageData* stack = this->Image;
  const vtkIdType perSlice = image->GetNumberOfPoints();
  if (k == 0)
  {
    this->AllocateLike(image);
  }
  vtkPointData* slice = image->GetPointData();
  for (int a = 0; a < slice->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* from = slice->GetArray(a);
    vtkDataArray* to = from ? stack->GetPointData()->GetArray(from->GetName()) : nullptr;
    if (to && to->GetNumberOfComponents() == from->GetNumberOfComponents())
    {
      to->InsertTuples(k * perSlice, perSlice, 0, from);
    }
  }
  vtkFieldData* fields = image->GetFieldData();
  for (int a = 0; a < fields->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* from = fields->GetArray(a);
    vtkDataArray* to = from ? stack->GetFieldData()->GetArray(from->GetName()) : nullptr;
    if (to && from->GetNumberOfTuples() == 1 &&
      to->GetNumberOfComponents() == from->GetNumberOfComponents())
    {
      to->SetTuple(k, 0, from);
    }
  }
}

void PoseStack::AllocateLike(vtkImageData* image)
{
  vtkImageData* stack = this->Image;
  const vtkIdType perSlice = image->GetNumberOfPoints();
  vtkPointData* slice = image->GetPointData();
  // The scalars fit (the constructor's check, before any work); the other
  // arrays are kept where they fit too.
  bool everyArray = this->EveryArray;
  if (everyArray)
  {
    double bytes = 0.0;
    for (int a = 0; a < slice->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* from = slice->GetArray(a);
      bytes += from ? static_cast<double>(perSlice) * this->Count * from->GetNumberOfComponents() *
          from->GetDataTypeSize()
                    : 0.0;
    }
    const std::string problem = mcx::MemoryProblem(bytes,
      "A stack of " + std::to_string(this->Count) + " poses' " +
        std::to_string(slice->GetNumberOfArrays()) + " arrays");
    if (!problem.empty())
    {
      everyArray = false;
      this->LeftOut = "the stack holds the scalars alone: " + problem;
    }
  }
  stack->SetOrigin(image->GetOrigin());
  stack->SetSpacing(image->GetSpacing()[0], image->GetSpacing()[1], 1.0);
  // Every point array (LineIntegral beside a radiograph's Intensity, the
  // channels), or the scalars alone; the image's scalars the stack's.
  for (int a = 0; a < slice->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* from = slice->GetArray(a);
    if (!from || !from->GetName() || (!everyArray && from != slice->GetScalars()))
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> values = EmptyLike(from, perSlice * this->Count);
    stack->GetPointData()->AddArray(values);
    if (from == slice->GetScalars())
    {
      stack->GetPointData()->SetActiveScalars(from->GetName());
    }
  }
  // Each one-tuple field (ProjectionMatrix, SampleCount, EstimatedRelativeError, ...) as a tuple
  // per pose.
  vtkFieldData* fields = image->GetFieldData();
  for (int a = 0; a < fields->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* from = fields->GetArray(a);
    if (!from || !from->GetName() || from->GetNumberOfTuples() != 1)
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> values = EmptyLike(from, this->Count);
    values->Fill(0.0);
    stack->GetFieldData()->AddArray(values);
  }
}

bool WritePoseGeometry(
  const std::vector<PoseRecord>& poses, const std::string& path, std::string& error)
{
  std::ostringstream out;
  out << std::setprecision(17);
  out << "{\n  \"convention\": \"P maps a world point (LPS, mm; x, y, z, 1) to (u w, v w, w): u "
         "the column from the left, v the row from the top, 0 at the first pixel's centre, w > 0 "
         "in front of the source; P = K [R | t] (OpenCV: camera x right, y down, z forward)\",\n"
      << "  \"poses\": [\n";
  for (std::size_t k = 0; k < poses.size(); ++k)
  {
    WritePose(out, poses[k]);
    out << (k + 1 < poses.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  return WriteFileAtomically(
    path,
    [&](const std::string& temporary)
    {
      std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
      file << out.str();
      file.close();
      return static_cast<bool>(file);
    },
    error);
}

} // namespace mcxapp
