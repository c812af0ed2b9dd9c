// The VIEW_ORDERED strategy of vtkMCXPointSampler: the ordering view
// (SetOrderingView's copy of a camera), the view order of the voxels sorted
// for it and kept while only the TF changes, the bins' images of the control
// projected once per sort, and the cloud drawn from that order with its
// weights and control image. Apart from the sampler because it is a method
// of its own with a cache of its own; the sampler dispatches to it.
#ifndef vtkMCXViewOrderedSamplingPrivate_h
#define vtkMCXViewOrderedSamplingPrivate_h

#include "mcxProjectionGeometry.h" // for Cloud
#include "vtkIndent.h"             // for PrintSelf
#include "vtkSmartPointer.h"       // for Cloud
#include "vtkType.h"               // for vtkIdType

#include <functional>
#include <memory>
#include <ostream>
#include <vector>

class vtkCamera;
class vtkFieldData;
class vtkFloatArray;
class vtkMCXPointSampler;
class vtkObject;
class vtkPoints;

namespace mcx
{
struct IndexView;
}

class vtkMCXViewOrderedSampling
{
public:
  vtkMCXViewOrderedSampling();
  ~vtkMCXViewOrderedSampling();

  /// SetOrderingView: copies the geometry of `camera` for an image of width
  /// x height pixels (a null camera or an empty size clears it); true when
  /// the view changed (the sampler is then modified). Errors go to `self`.
  bool SetView(vtkObject* self, vtkCamera* camera, int width, int height);
  bool HasView() const;

  /// Lets the kept view order go (another strategy runs); keeps the view.
  void ForgetOrder();

  /// A view-ordered cloud: its points and weights, its exponent, and the
  /// control image of the ordering view (empty: none) with that view and
  /// its own variance summed over the pixels.
  struct Cloud
  {
    vtkSmartPointer<vtkPoints> Points;
    vtkSmartPointer<vtkFloatArray> Weights;
    unsigned Exponent = 0;
    std::vector<double> Control;
    mcx::ProjectionGeometry ControlView;
    double ControlVariance = 0.0;
  };
  enum class Outcome
  {
    Made,
    Failed, // reported
    Aborted
  };
  /// A cloud's points of `type` and `count`; null (reported) when they
  /// cannot be allocated.
  using PointAllocator = std::function<vtkSmartPointer<vtkPoints>(int type, vtkIdType count)>;

  /// The cloud of `sampler`'s settings from `view` (prepared by
  /// mcx::PrepareSampling, of the given integral): the view order sorted
  /// (or the kept one), the bins' images projected for the control, then
  /// the points drawn.
  Outcome Sample(vtkMCXPointSampler* sampler, const mcx::IndexView& view, double integral,
    const PointAllocator& allocate, Cloud& cloud);

  /// Adds the cloud's control (when it has one) to a cloud's field data:
  /// the control image, its view, its variance and the control's points.
  static void WriteControl(const Cloud& cloud, vtkFieldData* fd);

  /// PrintSelf's lines of the ordering view and the kept order.
  void PrintSelf(std::ostream& os, vtkIndent indent) const;

private:
  /// SetOrderingView's copy of the camera's geometry.
  struct OrderingView;
  /// A view order and what it was sorted for.
  struct SortedView;

  /// The view order of `view` for the ordering view: the kept one when it
  /// fits, else sorted now; null after an error or an abort (`completed`).
  SortedView* ViewOrderFor(
    vtkMCXPointSampler* sampler, const mcx::IndexView& view, bool& completed);
  /// The bins' images of `sorted` for the control (kept, or projected now);
  /// false after an error or an abort (`completed`).
  bool ProjectBinsFor(
    vtkMCXPointSampler* sampler, const mcx::IndexView& view, SortedView& sorted, bool& completed);
  /// The cloud's points drawn from `order` under the TF's `weights`; false
  /// when they cannot be allocated, `completed` false when aborted.
  template <typename Order>
  bool Generate(vtkMCXPointSampler* sampler, const mcx::IndexView& view, const Order& order,
    const std::vector<double>& weights, double integral, const SortedView& sorted,
    const PointAllocator& allocate, Cloud& cloud, bool& completed);

  std::unique_ptr<OrderingView> Ordering; // null: none
  std::unique_ptr<SortedView> KeptViewOrder;
};

#endif
