/**
 * @class   vtkMCXAggregateIndex
 * @brief   Gathers a density index cut into z-slabs, one per process, into
 *          the whole volume's index on process 0.
 *
 * Under several processes (Controller) the filter asks its input, a
 * vtkMCXDensityIndex, for this process's z-slab of the volume (as
 * vtkMCXProjector does: each process reads and indexes only its slab), and
 * process 0 outputs the index of the whole volume: the same arrays, bit for
 * bit, as one process's vtkMCXDensityIndex of the whole volume. The other
 * processes output an empty image. With one process the output is the input.
 *
 * What crosses the network: the levels, as for vtkMCXProjector, and each
 * slab's voxel ids once (4 bytes a voxel; 8 above 2^32 voxels or with
 * AlwaysUseWideIds). Process 0 needs memory for the whole index besides its
 * own slab's.
 *
 * For consumers that need the whole index in one place: ParaView's "Monte
 * Carlo X-Ray" representation on a parallel server renders on one process;
 * a script can save or inspect the index of a volume read in pieces. Images
 * alone are cheaper with vtkMCXProjector, which keeps the index distributed.
 */
#ifndef vtkMCXAggregateIndex_h
#define vtkMCXAggregateIndex_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class vtkMultiProcessController;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXAggregateIndex : public vtkImageAlgorithm
{
public:
  static vtkMCXAggregateIndex* New();
  vtkTypeMacro(vtkMCXAggregateIndex, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The processes that hold the index's slabs (default: the global
   * controller). A problem on any process fails the filter on all of them,
   * with that process's message.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkMCXAggregateIndex();
  ~vtkMCXAggregateIndex() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkMCXAggregateIndex(const vtkMCXAggregateIndex&) = delete;
  void operator=(const vtkMCXAggregateIndex&) = delete;
};

#endif
