#include "mcxPoseOutput.h"

#include "mcxPartialFileGuard.h"
#include "mcxProjectionMatrix.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXTypes.h"
#include "vtkPointData.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <unistd.h>

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

void WritePose(std::ostream& out, vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  double P[12];
  image->GetFieldData()->GetArray(vtkMCXTypes::ProjectionMatrixName())->GetTuple(0, P);
  const int size[2] = { dims[0], dims[1] };
  out << "    {\"size\": ";
  WriteRow(out, std::vector<double>{ double(size[0]), double(size[1]) }.data(), 2);
  out << ", \"pixel_spacing\": ";
  WriteRow(out, image->GetSpacing(), 2);
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
  return Extension(path) == ".vti";
}

std::string NumberedOutput(const std::string& path, int index)
{
  const std::string extension = Extension(path);
  char number[16];
  std::snprintf(number, sizeof(number), "_%04d", index);
  return path.substr(0, path.size() - extension.size()) + number + extension;
}

vtkSmartPointer<vtkImageData> StackImages(const std::vector<vtkSmartPointer<vtkImageData>>& images)
{
  auto stack = vtkSmartPointer<vtkImageData>::New();
  vtkImageData* first = images.front();
  int dims[3];
  first->GetDimensions(dims);
  const int count = static_cast<int>(images.size());
  stack->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, count - 1);
  stack->SetOrigin(first->GetOrigin());
  stack->SetSpacing(first->GetSpacing()[0], first->GetSpacing()[1], 1.0);
  vtkDataArray* firstValues = first->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> values = vtk::TakeSmartPointer(firstValues->NewInstance());
  values->SetName(firstValues->GetName());
  const vtkIdType perSlice = static_cast<vtkIdType>(dims[0]) * dims[1];
  values->SetNumberOfTuples(perSlice * count);
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetName(vtkMCXTypes::ProjectionMatrixName());
  matrices->SetNumberOfComponents(12);
  matrices->SetNumberOfTuples(count);
  for (int k = 0; k < count; ++k)
  {
    vtkDataArray* slice = images[k]->GetPointData()->GetScalars();
    for (vtkIdType p = 0; p < perSlice; ++p)
    {
      values->SetTuple1(k * perSlice + p, slice->GetTuple1(p));
    }
    double P[12];
    images[k]->GetFieldData()->GetArray(vtkMCXTypes::ProjectionMatrixName())->GetTuple(0, P);
    matrices->SetTypedTuple(k, P);
  }
  stack->GetPointData()->SetScalars(values);
  stack->GetFieldData()->AddArray(matrices);
  return stack;
}

bool WritePoseGeometry(const std::vector<vtkSmartPointer<vtkImageData>>& images,
  const std::string& path, std::string& error)
{
  std::ostringstream out;
  out << std::setprecision(17);
  out << "{\n  \"convention\": \"P maps a world point (LPS, mm; x, y, z, 1) to (u w, v w, w): u "
         "the column from the left, v the row from the top, 0 at the first pixel's centre, w > 0 "
         "in front of the source; P = K [R | t] (OpenCV: camera x right, y down, z forward)\",\n"
      << "  \"poses\": [\n";
  for (std::size_t k = 0; k < images.size(); ++k)
  {
    WritePose(out, images[k]);
    out << (k + 1 < images.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  // All or nothing: a temporary beside the file, renamed when complete.
  const std::string temporary = path + ".part-" + std::to_string(getpid());
  const PartialFileGuard guard(temporary);
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << out.str();
    file.close();
    if (!file)
    {
      const int cause = errno;
      std::remove(temporary.c_str());
      error = "cannot write '" + path + "': " + std::strerror(cause);
      return false;
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const int cause = errno;
    std::remove(temporary.c_str());
    error = "cannot write '" + path + "': " + std::strerror(cause);
    return false;
  }
  return true;
}

} // namespace mcxapp
