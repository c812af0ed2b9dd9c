// The density index and the point sampler that vtkMCXXRayMapper owns when
// its input is image data rather than a point cloud: a volume is indexed
// once (again only when it or its density array changes), a density index
// (vtkMCXDensityIndex's output, as ParaView's representation delivers it) is
// used as it is, and the sampler re-samples under the volume property's TF
// in O(M) on every edit. A view-ordered sampler is sorted for the view when
// the TF or a sampling setting changed since its last sort, not when only
// the camera moved (the sort costs a pass over the voxels).
#ifndef vtkMCXVolumeSamplingPrivate_h
#define vtkMCXVolumeSamplingPrivate_h

#include "vtkNew.h"
#include "vtkType.h"

class vtkAlgorithmOutput;
class vtkCamera;
class vtkDataArray;
class vtkDataObject;
class vtkImageData;
class vtkMCXDensityIndex;
class vtkMCXPointSampler;
class vtkPiecewiseFunction;
class vtkPolyData;

class vtkMCXVolumeSampling
{
public:
  /// The mapper's sampling settings (see vtkMCXPointSampler).
  struct Settings
  {
    int SampleExponent;
    int Strategy;
    int Kernel;
    int Deposit;
    vtkTypeInt64 Seed;
    double ReorderAngle;
  };

  vtkMCXVolumeSampling();
  ~vtkMCXVolumeSampling();
  vtkMCXVolumeSampling(const vtkMCXVolumeSampling&) = delete;
  vtkMCXVolumeSampling& operator=(const vtkMCXVolumeSampling&) = delete;

  /// Whether data is a density index rather than a volume.
  static bool IsDensityIndex(vtkDataObject* data);

  /// Connects the sampler to input (its data: image): through the index of
  /// the point array density for a volume, directly for a density index
  /// (density is then unused).
  void Connect(vtkAlgorithmOutput* input, vtkImageData* image, vtkDataArray* density);

  /// Applies the settings (they re-sample only when they changed).
  void Configure(const Settings& settings);

  /// The cloud under tf, sorted for the camera's view of width x height
  /// pixels when the sampler is view-ordered and needs a sort; without an
  /// Integral when the index or the sampler failed (they reported it).
  vtkPolyData* Sample(vtkPiecewiseFunction* tf, vtkCamera* camera, const int size[2]);

  /// The world corners of the support of the TF's volume, known before any
  /// point is made; false when the index cannot tell.
  bool SupportCorners(double corners[24]);

  vtkMCXDensityIndex* GetIndex() { return this->Index; }
  vtkMCXPointSampler* GetSampler() { return this->Sampler; }

private:
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkMCXPointSampler> Sampler;
  vtkMTimeType SortedAt = 0; // the sampler's time after its last sort for a view
};

#endif
