/**
 * @class   vtkMCXPointSampler
 * @brief   Regenerates the point samples of hybrid Monte Carlo volume
 *          rendering from a density index under a transfer function.
 *
 * Input: the output of vtkMCXDensityIndex. Output: vtkPolyData with
 * M = 2^m - 1 points in world coordinates (spacing, origin and direction
 * applied) and no cells. Sample k is stored at index k: for the Hybrid and
 * QuasiMonteCarlo strategies this is the base-2 Halton order, so every
 * prefix of 2^j - 1 points is exactly the point set of a 2^j - 1 sample run
 * and gives a coarser estimate (progressive refinement).
 *
 * Each point stands for SampleWeight = Integral / M, where Integral is the
 * integral of g(x) = sum_ijk TF(f_ijk) h(x - x_ijk) over space (TF units
 * times world volume). Both travel in the output's field data
 * ("SampleWeight", "Integral", "SampleExponent"), and the world corners of
 * the support of g travel in the output information (SUPPORT_CORNERS) so that
 * projectors can frame the image before any point exists.
 *
 * The cost is O(M) and independent of the voxel count; a TF change
 * re-executes this filter only, never the index. The same seed gives the same
 * points for any number of threads. The EVERY_VOXEL strategy takes each voxel
 * of non-zero weight once instead, weighted (see SetStrategy).
 */
#ifndef vtkMCXPointSampler_h
#define vtkMCXPointSampler_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXTypes.h"                 // for the strategies, kernels and deposits
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for KeptPoints

#include <memory> // for EveryVoxel and ViewOrdered

class vtkCamera;
class vtkImageData;
class vtkInformationDoubleVectorKey;
class vtkMCXEveryVoxelSampling;
class vtkMCXViewOrderedSampling;
class vtkPiecewiseFunction;
class vtkPoints;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXPointSampler : public vtkPolyDataAlgorithm
{
public:
  static vtkMCXPointSampler* New();
  vtkTypeMacro(vtkMCXPointSampler, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Transfer function from data values to g (any non-negative unit); it is
   * clamped at its end points. Negative and NaN values count as 0.
   * Without one (the default), g is the data value itself.
   */
  virtual void SetTransferFunction(vtkPiecewiseFunction*);
  vtkGetObjectMacro(TransferFunction, vtkPiecewiseFunction);
  ///@}

  ///@{
  /**
   * M = 2^SampleExponent - 1 samples (default vtkMCXTypes::DefaultSampleExponent, 22).
   * SetNumberOfSamples(n) picks the smallest m with 2^m - 1 >= n.
   */
  vtkSetClampMacro(SampleExponent, int, 0, vtkMCXTypes::MaximumPointCloudExponent);
  vtkGetMacro(SampleExponent, int);
  void SetNumberOfSamples(vtkTypeInt64 n);
  vtkTypeInt64 GetNumberOfSamples();
  ///@}

  ///@{
  /**
   * How the points are chosen: HYBRID (default), MONTE_CARLO and
   * QUASI_MONTE_CARLO draw M = 2^SampleExponent - 1 samples, each voxel in
   * proportion to its TF weight. EVERY_VOXEL takes each voxel whose TF
   * weight is not zero once instead (SampleExponent is then unused), with
   * its weight in the point-data array PointWeight (mean 1, see
   * PointWeightName()), so the image has no voxel-choice noise; the cost of
   * a TF edit grows with those voxels, not with M. It pays where they are
   * fewer than the samples a target error needs with the footprint deposit
   * (Documentation/performance.md compares them). The points are the voxels in runs of 64
   * neighbours in voxel-id order, the runs in base-2 van der Corput (bit-reversed) order, so any
   * prefix is spread over the volume (the mapper's progressive refinement). With ReusePoints on, a
   * TF edit that keeps the same voxels rewrites only the weights. The output has no SampleExponent
   * field.
   *
   * VIEW_ORDERED draws M samples too, for voxels much smaller than the
   * pixels of one view (a 400 M-voxel CT at 256^2), where the Halton choice
   * over density levels gains little over plain Monte Carlo: the levels are
   * grouped into NumberOfOrderingBins bins of equal value width, each bin's
   * voxels sorted by the pixel of the view set with SetOrderingView, then
   * by the position in that pixel; a bin is drawn in proportion to its mass
   * and a voxel uniformly in it, with the weight w / (the bin's mean w) in
   * PointWeight. Unbiased for any camera; for the ordering view each pixel
   * gets its share of each bin to within one sample, spread over the
   * pixel's area, so the voxel choice adds little noise (measured: a 400
   * M-voxel CT at 256^2 needs 8 times fewer points than HYBRID for 2 %,
   * and 64 times fewer with the control image, SetControlVariate).
   * The sort is three passes over every voxel (there 1.5 times the index
   * build's time), done when the view, the bins or the index change and
   * kept while only the TF changes (and for a view turned by at most
   * ReorderAngle): it pays where one view takes many TF edits. The whole
   * volume must be in this process (not a piece of a distributed index).
   */
  vtkSetClampMacro(Strategy, int, vtkMCXTypes::HYBRID, vtkMCXTypes::VIEW_ORDERED);
  vtkGetMacro(Strategy, int);
  void SetStrategyToHybrid() { this->SetStrategy(vtkMCXTypes::HYBRID); }
  void SetStrategyToMonteCarlo() { this->SetStrategy(vtkMCXTypes::MONTE_CARLO); }
  void SetStrategyToQuasiMonteCarlo() { this->SetStrategy(vtkMCXTypes::QUASI_MONTE_CARLO); }
  void SetStrategyToEveryVoxel() { this->SetStrategy(vtkMCXTypes::EVERY_VOXEL); }
  void SetStrategyToViewOrdered() { this->SetStrategy(vtkMCXTypes::VIEW_ORDERED); }
  ///@}

  /**
   * The view of VIEW_ORDERED: the geometry of `camera` for an image of
   * width x height pixels (the renderer's size), copied now, so later
   * camera moves change nothing until this is called again (a viewer calls
   * it when a TF edit follows a camera move). The voxels are sorted by its
   * pixels (unless ReorderAngle keeps an order sorted for a nearby view)
   * and the control image is of it. A null camera or an empty size clears
   * it.
   */
  void SetOrderingView(vtkCamera* camera, int width, int height);
  /** Whether an ordering view is set. */
  bool HasOrderingView() const;

  ///@{
  /**
   * VIEW_ORDERED: how far, in degrees (0 to 180), a new ordering view may
   * turn (mcx::TurnDegrees: the rotation of the camera's axes, a roll
   * included) from the view the kept order was sorted for and still use
   * that order. Then only the control image is projected for the new view,
   * not the sort: a new view of a 400 M-voxel CT costs about an eighth of
   * the time, at more error for the same points (stratified by another
   * view's pixels; unbiased in any view, and the error estimate says how
   * much; Documentation/method.md measures both). The new view must frame
   * the volume's centre as the sorted one did (mcx::SameFraming, to 5 %:
   * a turn about it): a pan, a zoom, another image size or projection
   * sorts again. 0 (the default) sorts for every new view.
   */
  vtkSetClampMacro(ReorderAngle, double, 0.0, 180.0);
  vtkGetMacro(ReorderAngle, double);
  ///@}

  ///@{
  /**
   * The density bins of VIEW_ORDERED (default 16, 1 to 1024): more bins
   * mean less spread of the weight inside a bin but fewer voxels in each
   * (bin, pixel) cell to stratify.
   */
  vtkSetClampMacro(NumberOfOrderingBins, int, 1, 1024);
  vtkGetMacro(NumberOfOrderingBins, int);
  ///@}

  ///@{
  /**
   * VIEW_ORDERED: whether the output carries the control image of the
   * ordering view (default on), with which vtkMCXProjector and
   * vtkMCXXRayMapper cut the error of an image of that view (the same
   * camera and size, the prop's matrix the identity, nothing opaque in
   * front; measured on a 402 M-voxel CT at 256^2: 3.4 times at 2^19 - 1
   * points, 2.7 times at 2^21 - 1) at the same point count (mcxControlImage.h):
   * the image of the TF that is constant on each bin, its mean weight,
   * made from each bin's voxels projected (footprints of the Kernel; every
   * voxel once, or a sample, ControlVoxelsPerPoint) when the view order is
   * sorted, and then weighed per TF edit (a sum of NumberOfOrderingBins
   * images, not a pass over the voxels). It keeps 8 bytes per (bin,
   * pixel), 16 when sampled; a sampled one is made again when the Seed or
   * the SampleExponent changes.
   */
  vtkSetMacro(ControlVariate, bool);
  vtkGetMacro(ControlVariate, bool);
  vtkBooleanMacro(ControlVariate, bool);
  ///@}

  ///@{
  /**
   * VIEW_ORDERED with the control image: how many voxels it projects per
   * point of the cloud (default 64, at least 1). Where the volume has no
   * more than twice as many voxels per point, the control image projects
   * every voxel once; else about this many per point, at least two per
   * (bin, pixel) run, drawn systematically from each run of the view order
   * (mcx::ControlPicks: an unbiased estimate of every voxel's image, made
   * again for a new Seed or SampleExponent), and its own error joins the
   * image's estimate (vtkMCXTypes::ControlVarianceName()). Fewer voxels
   * per point cost less time per view and add more error
   * (Documentation/method.md measures both).
   */
  vtkSetClampMacro(ControlVoxelsPerPoint, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ControlVoxelsPerPoint, double);
  ///@}

  ///@{
  vtkSetClampMacro(Kernel, int, vtkMCXTypes::TENT, vtkMCXTypes::BOX);
  vtkGetMacro(Kernel, int);
  void SetKernelToTent() { this->SetKernel(vtkMCXTypes::TENT); }
  void SetKernelToBox() { this->SetKernel(vtkMCXTypes::BOX); }
  ///@}

  ///@{
  /**
   * FOOTPRINT (default): each point is the chosen voxel's centre, and
   * projectors (vtkMCXProjector, vtkMCXXRayMapper) deposit the voxel's
   * kernel footprint over the pixels it reaches (see vtkMCXProjector).
   * POINT (the paper's): each point is a sample's position, its voxel
   * centre plus a random offset from the kernel, and projectors count it
   * where it lands: the same memory per point, far more noise. The choice
   * travels in the field data.
   */
  vtkSetClampMacro(Deposit, int, vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT);
  vtkGetMacro(Deposit, int);
  void SetDepositToPoint() { this->SetDeposit(vtkMCXTypes::POINT); }
  void SetDepositToFootprint() { this->SetDeposit(vtkMCXTypes::FOOTPRINT); }
  ///@}

  ///@{
  /** Seed of the pseudo-random parts, 0 to 2^63 - 1 (default 0). */
  vtkSetClampMacro(Seed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(Seed, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Keep the cloud's points between executions and refill them in place
   * when their type and count fit and nothing else holds them (default
   * off): a TF edit then fills memory that is already mapped. Allocating
   * the cloud again costs little below glibc's 32 MiB mmap limit (the heap
   * recycles the block) but above it the block is unmapped and faulted in
   * again page by page, which costs several regenerations' time
   * (Documentation/performance.md has the measurement). Points that something else still holds (a shallow copy, a
   * reference from Python, their array taken out) are never rewritten: the
   * cloud then gets new ones. The price: while it is on, the sampler holds
   * the last cloud's memory even after the pipeline releases its output
   * (turning it off lets go). Interactive pipelines whose consumer is the
   * mapper turn it on (the viewer, the ParaView representation).
   */
  virtual void SetReusePoints(bool reuse);
  vtkGetMacro(ReusePoints, bool);
  vtkBooleanMacro(ReusePoints, bool);
  ///@}

  ///@{
  /**
   * vtkAlgorithm::SINGLE_PRECISION (default) or DOUBLE_PRECISION points.
   */
  vtkSetClampMacro(OutputPointsPrecision, int, SINGLE_PRECISION, DOUBLE_PRECISION);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  /**
   * World coordinates of the 8 corners of the support of g (24 doubles),
   * set on the output information by RequestInformation.
   */
  static vtkInformationDoubleVectorKey* SUPPORT_CORNERS();

  vtkMTimeType GetMTime() override;

protected:
  vtkMCXPointSampler();
  ~vtkMCXPointSampler() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPiecewiseFunction* TransferFunction = nullptr;
  int SampleExponent = vtkMCXTypes::DefaultSampleExponent;
  int Strategy = vtkMCXTypes::HYBRID;
  int Kernel = vtkMCXTypes::TENT;
  int Deposit = vtkMCXTypes::FOOTPRINT;
  vtkTypeInt64 Seed = 0;
  bool ReusePoints = false;
  int OutputPointsPrecision = SINGLE_PRECISION;
  /// The last cloud's points, kept for ReusePoints.
  vtkSmartPointer<vtkPoints> KeptPoints;
  int NumberOfOrderingBins = 16;
  bool ControlVariate = true;
  double ControlVoxelsPerPoint = 64.0;
  double ReorderAngle = 0.0;
  /// EVERY_VOXEL, with its kept cloud (vtkMCXEveryVoxelSamplingPrivate.h).
  std::unique_ptr<vtkMCXEveryVoxelSampling> EveryVoxel;
  /// VIEW_ORDERED: SetOrderingView's geometry and the kept sort
  /// (vtkMCXViewOrderedSamplingPrivate.h).
  std::unique_ptr<vtkMCXViewOrderedSampling> ViewOrdered;

private:
  /// RequestData's work, which may throw std::bad_alloc (caught there).
  int RequestCloud(vtkImageData* input, vtkPolyData* output);
  /// RequestData of HYBRID, MONTE_CARLO and QUASI_MONTE_CARLO.
  int RequestSampled(vtkImageData* input, vtkPolyData* output);
  /// RequestData of VIEW_ORDERED.
  int RequestViewOrdered(vtkImageData* input, vtkPolyData* output);
  /// A cloud's points: KeptPoints refilled, or new ones; null (and an
  /// error) when `count` points cannot be allocated.
  vtkSmartPointer<vtkPoints> CloudPoints(vtkPolyData* output, int type, vtkIdType count);

  /// KeptPoints when ReusePoints allows to refill them: of `type` and
  /// `count`, held by nothing but this filter and `output`; else null.
  vtkPoints* ReusablePoints(vtkPolyData* output, int type, vtkIdType count) const;

  vtkMCXPointSampler(const vtkMCXPointSampler&) = delete;
  void operator=(const vtkMCXPointSampler&) = delete;
};

#endif
