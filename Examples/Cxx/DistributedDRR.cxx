// A DRR of a volume too large for one machine, on MPI: every process reads
// and indexes only its z-slab (the XML reader reads just those slices) and
// deposits the samples whose voxels it holds; the processes add their exact
// sums, and the first writes the image, the same file for any process count.
//
//   mpirun -np 4 DistributedDRR volume.vti output.vti [log2 samples]
#include "vtkMCXDensityIndex.h"
#include "vtkMCXProjector.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <cstdlib>
#include <iostream>

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller); // the filters' default
  const bool first = controller->GetLocalProcessId() == 0;
  if (argc < 3)
  {
    if (first)
    {
      std::cerr << "usage: mpirun -np N DistributedDRR volume.vti output.vti [log2 samples]\n";
    }
    controller->Finalize();
    return 2;
  }

  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(argv[1]);
  vtkNew<vtkMCXDensityIndex> index; // indexes the slab the projector asks for
  index->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkPiecewiseFunction> tf; // CT in HU to attenuation per mm, 0 at air
  tf->AddPoint(-1000, 0.0);
  tf->AddPoint(3000, 0.08);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetDepositToFootprint();
  projector->SetSampleExponent(argc > 3 ? std::atoi(argv[3]) : 22);
  projector->SetImageSize(256, 256);
  projector->Update();

  // The image is process 0's output (the others' are empty); an error
  // (reported) leaves it empty too.
  vtkImageData* image = projector->GetOutput();
  int made = image->GetNumberOfPoints() > 0 ? 1 : 0;
  controller->Broadcast(&made, 1, 0);
  if (made && first)
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(argv[2]);
    writer->Write();
    std::cout << controller->GetNumberOfProcesses() << " processes, "
              << static_cast<long long>(image->GetFieldData()->GetArray("SampleCount")->GetTuple1(0))
              << " samples, estimated relative error "
              << image->GetFieldData()->GetArray("EstimatedRelativeError")->GetTuple1(0)
              << ", wrote " << argv[2] << std::endl;
  }
  controller->Finalize();
  return made ? 0 : 1;
}
