// Distributed rendering under MPI (run by ctest with mpiexec -np 1, 2 and 3):
// every process reads and indexes only its z-slab of the volume, deposits
// the samples whose voxels it holds, and the processes add their exact sums.
// Process 0's image must be, bit for bit, the one a single process makes of
// the whole volume (computed here too, with no controller),
// for point and footprint deposits, every strategy, parallel and perspective
// views, float data, more processes than slices, and a transfer function
// that is zero on some pieces or everywhere; a process that cannot index its
// piece fails every process with its message, and none waits forever.
// The index gathered onto process 0 (vtkMCXAggregateIndex) is, array for
// array, one process's index of the whole volume.
#include "mcxTestHelpers.h"
#include "vtkMCXAggregateIndex.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXDistributed.h"
#include "vtkMPIController.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
vtkMultiProcessController* Controller()
{
  return vtkMultiProcessController::GetGlobalController();
}

struct Settings
{
  int Strategy = vtkMCXTypes::HYBRID;
  int Deposit = vtkMCXTypes::POINT;
  bool Perspective = false;
  double TargetError = 0.0;
};

vtkSmartPointer<vtkCamera> ObliquePerspective()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(120, 110, 90);
  camera->SetPosition(-300, -180, 420);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(40);
  camera->SetClippingRange(10, 2000);
  return camera;
}

// The image of an index pipeline's output; distributed when `controller`
// is set (the index then reads only its slab through the pipeline).
vtkSmartPointer<vtkImageData> Project(vtkAlgorithmOutput* volume, vtkPiecewiseFunction* tf,
  const Settings& settings, vtkMultiProcessController* controller)
{
  vtkNew<vtkMCXDensityIndex> index;
  index->SetController(controller);
  index->SetInputConnection(volume);
  vtkNew<vtkMCXProjector> projector;
  projector->SetController(controller);
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetStrategy(settings.Strategy);
  projector->SetDeposit(settings.Deposit);
  projector->SetSampleExponent(18);
  projector->SetSeed(7);
  projector->SetTargetRelativeError(settings.TargetError);
  projector->SetMaximumSampleExponent(20);
  projector->SetImageSize(96, 80);
  if (settings.Perspective)
  {
    projector->SetCamera(ObliquePerspective());
  }
  projector->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(projector->GetOutput());
  return image;
}

// Bit-for-bit equality of two projector outputs, with their sample counts
// and error estimates, on process 0; the other processes' images are empty.
void ExpectSameImage(vtkImageData* serial, vtkImageData* distributed, const std::string& what)
{
  if (Controller()->GetLocalProcessId() != 0)
  {
    EXPECT_EQ(0, distributed->GetNumberOfPoints()) << what;
    return;
  }
  vtkDataArray* a = mcxtest::LineIntegral(serial);
  vtkDataArray* b = mcxtest::LineIntegral(distributed);
  ASSERT_NE(nullptr, a) << what;
  ASSERT_NE(nullptr, b) << what;
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << what;
  vtkIdType differing = 0;
  double sum = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    differing += a->GetTuple1(i) != b->GetTuple1(i) ? 1 : 0;
    sum += a->GetTuple1(i);
  }
  EXPECT_EQ(0, differing) << what << " on process " << Controller()->GetLocalProcessId();
  EXPECT_GT(sum, 0.0) << what;
  for (const char* name : { "SampleCount", "EstimatedRelativeError", "Integral" })
  {
    const double expected = mcxtest::FieldValue(serial, name);
    const double got = mcxtest::FieldValue(distributed, name);
    EXPECT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected)))
      << what << ": " << name << " " << got << " instead of " << expected;
  }
}

vtkSmartPointer<vtkPiecewiseFunction> Ramp(double lo, double hi)
{
  auto tf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  tf->AddPoint(lo, 0.0);
  tf->AddPoint(hi, 1.0);
  return tf;
}

// An 8 x 8 x 6 volume, given as data to every process; the last process's
// has no scalars.
vtkSmartPointer<vtkImageData> VolumeWithoutScalarsOnTheLastProcess()
{
  const int dims[3] = { 8, 8, 6 };
  auto volume =
    mcxtest::MakeVolume(VTK_SHORT, dims, [](int i, int j, int k) { return i + j + k; });
  if (Controller()->GetLocalProcessId() == Controller()->GetNumberOfProcesses() - 1)
  {
    volume->GetPointData()->Initialize();
  }
  return volume;
}

// A volume held by a trivial producer: the index crops each process's slab.
vtkSmartPointer<vtkTrivialProducer> Produce(vtkImageData* volume)
{
  auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
  producer->SetOutput(volume);
  return producer;
}
}

TEST(Distributed, ImagesAreTheSingleProcessImagesBitForBit)
{
  // The bundled CT head read as pieces by VTK's XML reader (each process
  // reads its slab's slices).
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  auto tf = Ramp(500, 3000);
  for (const bool perspective : { false, true })
  {
    for (const int deposit : { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT })
    {
      // Every voxel too: each process deposits its slab's voxels, numbered
      // by their ids in the whole volume.
      for (const int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::QUASI_MONTE_CARLO,
             vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::EVERY_VOXEL })
      {
        Settings settings;
        settings.Strategy = strategy;
        settings.Deposit = deposit;
        settings.Perspective = perspective;
        const std::string what = std::string(perspective ? "perspective" : "parallel") +
          (deposit == vtkMCXTypes::POINT ? " point" : " footprint") + " strategy " +
          std::to_string(strategy);
        ExpectSameImage(Project(reader->GetOutputPort(), tf, settings, nullptr),
          Project(reader->GetOutputPort(), tf, settings, Controller()), what);
      }
    }
  }
}

TEST(Distributed, TargetErrorChoosesTheSameSampleCount)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  auto tf = Ramp(500, 3000);
  Settings settings;
  settings.TargetError = 0.05;
  settings.Deposit = vtkMCXTypes::FOOTPRINT;
  ExpectSameImage(Project(reader->GetOutputPort(), tf, settings, nullptr),
    Project(reader->GetOutputPort(), tf, settings, Controller()), "target error");
}

TEST(Distributed, FloatDataIsBinnedAlikeOnEveryPiece)
{
  // Float values whose bins each hold voxels of every slab, with values a
  // little apart within a bin (the offsets 0.0001 (k mod 3), under the bin
  // width): a level is the mean of its voxels over the whole volume, and the
  // images agree only if every process computes that same mean.
  const int dims[3] = { 23, 19, 17 };
  auto volume = mcxtest::MakeVolume(VTK_FLOAT, dims,
    [](int i, int j, int k)
    { return std::floor(8 * std::sin(0.7 * i + 1.3 * j)) / 8 + 0.0001 * (k % 3) + 0.37; });
  auto producer = Produce(volume);
  vtkAlgorithmOutput* port = producer->GetOutputPort();
  auto tf = Ramp(-1.0, 1.5);
  for (const int deposit : { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT })
  {
    Settings settings;
    settings.Deposit = deposit;
    ExpectSameImage(Project(port, tf, settings, nullptr), Project(port, tf, settings, Controller()),
      deposit == vtkMCXTypes::POINT ? "float point" : "float footprint");
  }
}

TEST(Distributed, MoreProcessesThanSlicesAndZeroWeightPieces)
{
  // Two slices: with three processes one holds nothing. The TF is zero on
  // the lower slice, so the process holding it deposits nothing either.
  const int dims[3] = { 12, 9, 2 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [](int i, int j, int k) { return 100 * k + (i * 3 + j) % 7; });
  auto producer = Produce(volume);
  vtkAlgorithmOutput* port = producer->GetOutputPort();
  auto tf = Ramp(99, 110);
  for (const bool perspective : { false, true })
  {
    for (const int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::EVERY_VOXEL })
    {
      Settings settings;
      settings.Perspective = perspective;
      settings.Deposit = vtkMCXTypes::FOOTPRINT;
      settings.Strategy = strategy;
      ExpectSameImage(Project(port, tf, settings, nullptr),
        Project(port, tf, settings, Controller()),
        std::string(perspective ? "two slices, perspective" : "two slices, parallel") +
          " strategy " + std::to_string(strategy));
    }
  }
}

TEST(Distributed, SumsBeyondFortyEightBitsStayExact)
{
  // About 2^20 samples in each of 4 pixels: sums of 2^52 in fixed point,
  // past the first 48-bit limb of the exchange.
  const int dims[3] = { 6, 5, 7 };
  auto volume =
    mcxtest::MakeVolume(VTK_SHORT, dims, [](int i, int j, int k) { return (i + 2 * j + 3 * k) % 5; });
  auto producer = Produce(volume);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputConnection(producer->GetOutputPort());
  vtkNew<vtkMCXDensityIndex> wholeIndex;
  wholeIndex->SetController(nullptr);
  wholeIndex->SetInputConnection(producer->GetOutputPort());
  auto tf = Ramp(-1, 4);
  vtkSmartPointer<vtkImageData> images[2];
  for (int distributed = 0; distributed < 2; ++distributed)
  {
    vtkNew<vtkMCXProjector> projector;
    projector->SetController(distributed ? Controller() : nullptr);
    projector->SetInputConnection((distributed ? index : wholeIndex)->GetOutputPort());
    projector->SetTransferFunction(tf);
    projector->SetSampleExponent(22);
    projector->SetImageSize(2, 2);
    projector->Update();
    images[distributed] = vtkSmartPointer<vtkImageData>::New();
    images[distributed]->DeepCopy(projector->GetOutput());
  }
  ExpectSameImage(images[0], images[1], "2 x 2 pixels, 2^22 - 1 samples");
}

TEST(Distributed, ZeroTransferFunctionGivesAnEmptyImageEverywhere)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  vtkNew<vtkPiecewiseFunction> zero;
  zero->AddPoint(0, 0);
  zero->AddPoint(4000, 0);
  auto image = Project(reader->GetOutputPort(), zero, Settings(), Controller());
  if (Controller()->GetLocalProcessId() != 0)
  {
    EXPECT_EQ(0, image->GetNumberOfPoints());
    return;
  }
  vtkDataArray* values = mcxtest::LineIntegral(image);
  ASSERT_NE(nullptr, values);
  EXPECT_EQ(0.0, values->GetRange()[1]);
  EXPECT_EQ(0.0, mcxtest::FieldValue(image, "SampleCount"));
}

TEST(Distributed, AProcessThatCannotIndexItsPieceFailsEveryProcess)
{
  // The last process's volume has no scalars: every process's index fails
  // with that process's message, and the projector makes no image.
  vtkMultiProcessController* controller = Controller();
  const int last = controller->GetNumberOfProcesses() - 1;
  auto volume = VolumeWithoutScalarsOnTheLastProcess();
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetImageSize(32, 32);
  vtkNew<vtkMCXFirstErrorObserver> errors;
  errors->ObserveAlgorithm(index);
  vtkNew<vtkMCXFirstErrorObserver> projectorErrors;
  projectorErrors->ObserveAlgorithm(projector);
  projector->Update();
  const std::string expected =
    (controller->GetNumberOfProcesses() > 1
        ? "process " + std::to_string(last) + " of " +
          std::to_string(controller->GetNumberOfProcesses()) + ": "
        : std::string()) +
    "The input image has no point scalars to index.";
  EXPECT_EQ(expected, errors->GetErrorText());
  EXPECT_EQ(0, projector->GetOutput()->GetNumberOfPoints());
  errors->StopObserving();
  projectorErrors->StopObserving();
}

TEST(Distributed, AnIndexGivenAsDataIsRefusedNotCountedTwice)
{
  // An index handed to the projector as data is the whole volume on every
  // process; summed over the processes it would count each voxel N times.
  // Distributed, it is refused on every process with a hint; on one process
  // it is the ordinary whole index.
  const int dims[3] = { 8, 7, 6 };
  auto volume =
    mcxtest::MakeVolume(VTK_SHORT, dims, [](int i, int j, int k) { return 1 + (i + j + k) % 4; });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetController(nullptr);
  index->SetInputData(volume);
  index->Update();
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputData(index->GetOutput());
  projector->SetImageSize(16, 16);
  vtkNew<vtkMCXFirstErrorObserver> errors;
  errors->ObserveAlgorithm(projector);
  projector->Update();
  errors->StopObserving();
  if (Controller()->GetNumberOfProcesses() == 1)
  {
    EXPECT_EQ("", errors->GetErrorText());
    EXPECT_GT(projector->GetOutput()->GetNumberOfPoints(), 0);
    return;
  }
  EXPECT_NE(std::string::npos, errors->GetErrorText().find("is not this process's z-slab"))
    << errors->GetErrorText();
  EXPECT_EQ(0, projector->GetOutput()->GetNumberOfPoints());
}

namespace
{
// The index of the whole volume, gathered from the processes' slabs onto
// process 0, and one process's index of the same volume: the same geometry
// and arrays, value for value and type for type. Elsewhere: an empty output.
void ExpectAggregatedIndexIsTheWholeIndex(
  vtkAlgorithmOutput* volume, bool wideIds, const std::string& what)
{
  vtkNew<vtkMCXDensityIndex> wholeIndex;
  wholeIndex->SetController(nullptr);
  wholeIndex->SetAlwaysUseWideIds(wideIds);
  wholeIndex->SetInputConnection(volume);
  wholeIndex->Update();
  vtkImageData* serial = wholeIndex->GetOutput();

  vtkNew<vtkMCXDensityIndex> index;
  index->SetAlwaysUseWideIds(wideIds);
  index->SetInputConnection(volume);
  vtkNew<vtkMCXAggregateIndex> aggregate;
  aggregate->SetInputConnection(index->GetOutputPort());
  aggregate->Update();
  vtkImageData* gathered = aggregate->GetOutput();
  if (Controller()->GetLocalProcessId() != 0)
  {
    EXPECT_EQ(0, gathered->GetNumberOfPoints()) << what;
    EXPECT_EQ(0, gathered->GetFieldData()->GetNumberOfArrays()) << what;
    return;
  }
  int a[6], b[6];
  serial->GetExtent(a);
  gathered->GetExtent(b);
  EXPECT_TRUE(std::equal(a, a + 6, b)) << what;
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(serial->GetOrigin()[c], gathered->GetOrigin()[c]) << what;
    EXPECT_EQ(serial->GetSpacing()[c], gathered->GetSpacing()[c]) << what;
  }
  for (int c = 0; c < 9; ++c)
  {
    EXPECT_EQ(serial->GetDirectionMatrix()->GetData()[c], gathered->GetDirectionMatrix()->GetData()[c])
      << what;
  }
  vtkFieldData* expected = serial->GetFieldData();
  ASSERT_EQ(expected->GetNumberOfArrays(), gathered->GetFieldData()->GetNumberOfArrays()) << what;
  for (int i = 0; i < expected->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* x = expected->GetArray(i);
    vtkDataArray* y = gathered->GetFieldData()->GetArray(x->GetName());
    ASSERT_NE(nullptr, y) << what << ": " << x->GetName();
    EXPECT_EQ(x->GetDataType(), y->GetDataType()) << what << ": " << x->GetName();
    ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples()) << what << ": " << x->GetName();
    vtkIdType differing = 0;
    for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
    {
      differing += x->GetVariantValue(t) == y->GetVariantValue(t) ? 0 : 1;
    }
    EXPECT_EQ(0, differing) << what << ": " << x->GetName();
  }
}
}

TEST(Distributed, TheAggregatedIndexIsTheSingleProcessIndex)
{
  // The CT head read in slabs; float data whose levels are means over the
  // whole volume; two slices for three processes (a slab with nothing,
  // process 0's among them); 64-bit ids.
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  ExpectAggregatedIndexIsTheWholeIndex(reader->GetOutputPort(), false, "CT head");
  ExpectAggregatedIndexIsTheWholeIndex(reader->GetOutputPort(), true, "CT head, 64-bit ids");
  {
    // Each process reads only its slab: whole slices, as evenly as they
    // divide (a reader of its own, which no whole-volume request has read).
    vtkNew<vtkXMLImageDataReader> slabReader;
    slabReader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
    vtkNew<vtkMCXDensityIndex> slabIndex;
    slabIndex->SetInputConnection(slabReader->GetOutputPort());
    vtkNew<vtkMCXAggregateIndex> slabAggregate;
    slabAggregate->SetInputConnection(slabIndex->GetOutputPort());
    slabAggregate->Update();
    int whole[6], read[6];
    slabReader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    slabReader->GetOutput()->GetExtent(read);
    const int processes = Controller()->GetNumberOfProcesses();
    const int rank = Controller()->GetLocalProcessId();
    const int slices = whole[5] - whole[4] + 1;
    EXPECT_EQ(whole[4] + slices * rank / processes, read[4]);
    EXPECT_EQ(whole[4] + slices * (rank + 1) / processes - 1, read[5]);
    EXPECT_EQ(whole[0], read[0]);
    EXPECT_EQ(whole[3], read[3]);
  }
  const int floatDims[3] = { 23, 19, 17 };
  auto floats = Produce(mcxtest::MakeVolume(VTK_FLOAT, floatDims,
    [](int i, int j, int k)
    { return std::floor(8 * std::sin(0.7 * i + 1.3 * j)) / 8 + 0.0001 * (k % 3) + 0.37; }));
  ExpectAggregatedIndexIsTheWholeIndex(floats->GetOutputPort(), false, "float data");
  const int thinDims[3] = { 12, 9, 2 };
  auto thin = Produce(mcxtest::MakeVolume(
    VTK_SHORT, thinDims, [](int i, int j, int k) { return 100 * k + (i * 3 + j) % 7; }));
  ExpectAggregatedIndexIsTheWholeIndex(thin->GetOutputPort(), false, "two slices");
}

TEST(Distributed, AnAggregateOfAFailedIndexFailsEveryProcess)
{
  // The last process's slab has no scalars: the index fails there, and every
  // process's aggregate says so instead of waiting for its ids.
  auto volume = VolumeWithoutScalarsOnTheLastProcess();
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkMCXAggregateIndex> aggregate;
  aggregate->SetInputConnection(index->GetOutputPort());
  vtkNew<vtkMCXFirstErrorObserver> indexErrors;
  indexErrors->ObserveAlgorithm(index);
  aggregate->Update();
  indexErrors->StopObserving();
  EXPECT_NE(std::string::npos, indexErrors->GetErrorText().find("no point scalars"));
  EXPECT_EQ(0, aggregate->GetOutput()->GetFieldData()->GetNumberOfArrays());
}

namespace
{
// A source of a 10 x 9 x 8 volume that fails on one process, in its data
// object, its information or its data (as a reader of a missing or broken
// file: VTK's legacy readers fail in their data object).
class FailingSource : public vtkImageAlgorithm
{
public:
  enum Pass
  {
    DataObject,
    Information,
    Data
  };
  static FailingSource* New();
  vtkTypeMacro(FailingSource, vtkImageAlgorithm);
  int FailingProcess = -1;
  Pass FailingPass = Data;

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out) override
  {
    if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()) && this->FailsHere() &&
      this->FailingPass == DataObject)
    {
      vtkErrorMacro("Cannot tell what the file holds.");
      return 0;
    }
    return this->Superclass::ProcessRequest(request, in, out);
  }

protected:
  FailingSource() { this->SetNumberOfInputPorts(0); }
  bool FailsHere() const { return Controller()->GetLocalProcessId() == this->FailingProcess; }
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    if (this->FailsHere() && this->FailingPass == Information)
    {
      vtkErrorMacro("Cannot open the file.");
      return 0;
    }
    const int whole[6] = { 0, 9, 0, 8, 0, 7 };
    out->GetInformationObject(0)->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    vtkDataObject::SetPointDataActiveScalarInfo(out->GetInformationObject(0), VTK_SHORT, 1);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    if (this->FailsHere() && this->FailingPass == Data)
    {
      vtkErrorMacro("The file is truncated.");
      return 0;
    }
    vtkInformation* info = out->GetInformationObject(0);
    int extent[6];
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
    vtkImageData* image = vtkImageData::GetData(info);
    image->SetExtent(extent);
    image->AllocateScalars(VTK_SHORT, 1);
    auto* values = static_cast<short*>(image->GetScalarPointer());
    for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p)
    {
      values[p] = static_cast<short>(1 + p % 7);
    }
    return 1;
  }
};
vtkStandardNewMacro(FailingSource);
}

TEST(Distributed, AReaderThatFailsOnOneProcessFailsEveryProcess)
{
  // The last process's reader fails, in its data object, its information or
  // its data:
  // the index still meets the others and fails everywhere with that
  // process's message; the projector makes no image and no process waits.
  // On one process the pipeline stops at the reader, as VTK's does.
  vtkMultiProcessController* controller = Controller();
  const int processes = controller->GetNumberOfProcesses();
  for (const auto pass : { FailingSource::Data, FailingSource::Information, FailingSource::DataObject })
  {
    vtkNew<FailingSource> source;
    source->FailingProcess = processes - 1;
    source->FailingPass = pass;
    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputConnection(source->GetOutputPort());
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputConnection(index->GetOutputPort());
    projector->SetImageSize(16, 16);
    vtkNew<vtkMCXFirstErrorObserver> readerErrors, indexErrors, projectorErrors;
    readerErrors->ObserveAlgorithm(source);
    indexErrors->ObserveAlgorithm(index);
    projectorErrors->ObserveAlgorithm(projector);
    projector->Update();
    readerErrors->StopObserving();
    indexErrors->StopObserving();
    projectorErrors->StopObserving();
    const std::string where = pass == FailingSource::Data ? "data"
      : pass == FailingSource::Information              ? "information"
                                                        : "data object";
    if (processes == 1)
    {
      EXPECT_NE("", readerErrors->GetErrorText()) << where;
      EXPECT_EQ("", indexErrors->GetErrorText()) << where;
    }
    else
    {
      EXPECT_EQ("process " + std::to_string(processes - 1) + " of " + std::to_string(processes) +
          ": The volume's piece could not be read (see the reader's error in that process's output).",
        indexErrors->GetErrorText())
        << where;
    }
    // (No output at all where the pipeline stopped before making one.)
    vtkImageData* image = projector->GetOutput();
    EXPECT_EQ(0, image ? image->GetNumberOfPoints() : 0) << where;
    if (processes > 1)
    {
      // The index asked again, for this process's slab: every process goes
      // the same way (the failed index describes the same empty volume
      // everywhere), so none waits for another, and no index is made.
      int slab[6];
      const int whole[6] = { 0, 9, 0, 8, 0, 7 };
      mcx::ZSlabExtent(whole, controller->GetLocalProcessId(), processes, slab);
      vtkNew<vtkMCXFirstErrorObserver> againErrors;
      againErrors->ObserveAlgorithm(index);
      index->UpdateExtent(slab);
      againErrors->StopObserving();
      EXPECT_EQ(0, index->GetOutput()->GetFieldData()->GetNumberOfArrays()) << where;
    }
  }
}

TEST(Distributed, ASecondUpdateRunsNothingOnAnyProcess)
{
  // Process 0 holds the result and the others an empty output: without the
  // pipeline being told that the empty output meets the request, a second
  // update would run the filter again on the other processes alone, and
  // they would wait for process 0 forever. Each filter runs once everywhere.
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkMCXAggregateIndex> aggregate;
  aggregate->SetInputConnection(index->GetOutputPort());
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetImageSize(32, 24);
  projector->SetSampleExponent(14);
  for (vtkAlgorithm* filter : { static_cast<vtkAlgorithm*>(aggregate), static_cast<vtkAlgorithm*>(projector) })
  {
    int runs = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&runs);
    counter->SetCallback([](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    filter->AddObserver(vtkCommand::EndEvent, counter);
    filter->Update();
    filter->Update();
    filter->GetOutputInformation(0)->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      filter->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
    filter->Update();
    filter->RemoveObserver(counter);
    EXPECT_EQ(1, runs) << filter->GetClassName() << " on process " << Controller()->GetLocalProcessId();
  }
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  ::testing::InitGoogleTest(&argc, argv);
  if (controller->GetLocalProcessId() != 0)
  {
    // One report: the others fail through their exit code.
    ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int result = RUN_ALL_TESTS();
  int worst = 0;
  controller->AllReduce(&result, &worst, 1, vtkCommunicator::MAX_OP);
  controller->Finalize();
  return worst;
}
