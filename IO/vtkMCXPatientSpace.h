/**
 * @class   vtkMCXPatientSpace
 * @brief   The world every MonteCarloXRay reader places a volume in: DICOM
 *          patient coordinates (LPS), and the checks a placement must pass.
 *
 * LPS: x runs to the patient's left, y to the posterior, z to the head; the
 * convention of DICOM, ITK, plastimatch and radiotherapy planning. A reader
 * whose format states another world (a NIfTI sform is RAS, a NRRD header
 * names its space) converts into it; a placement that cannot be honoured (a
 * non-finite or singular direction matrix, a zero or non-finite spacing, a
 * corner beyond LargestCoordinate) is an error, never an axis-aligned guess.
 */
#ifndef vtkMCXPatientSpace_h
#define vtkMCXPatientSpace_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for the messages

class vtkImageData;

class MONTECARLOXRAYIO_EXPORT vtkMCXPatientSpace : public vtkObject
{
public:
  static vtkMCXPatientSpace* New();
  vtkTypeMacro(vtkMCXPatientSpace, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * No voxel may lie farther than this from the world origin along any
   * axis (1e9 world units: a kilometre in micrometres). Beyond it the
   * projection's double arithmetic has lost the voxel's size.
   */
  static double GetLargestCoordinate() { return 1e9; }

  /**
   * The reason volume's geometry cannot be placed (spacing, origin, direction
   * matrix and extent as above), or "" when it can.
   */
  static std::string DescribeUnusablePlacement(vtkImageData* volume);

  /**
   * Splits the world step of one voxel along each axis (steps[3 * r + a]:
   * row r of axis a's step, the columns of a header's matrix) into spacing
   * (the steps' lengths) and unit directions (direction[3 * r + a]).
   * Returns "" on success, else the reason (a zero or non-finite step,
   * directions that span no volume).
   */
  static std::string SplitAxisSteps(const double steps[9], double spacing[3], double direction[9]);

  /**
   * The reason an origin and extent cannot be placed with spacing and
   * direction (a non-finite origin, a corner beyond GetLargestCoordinate()),
   * or "".
   */
  static std::string DescribeUnusableExtent(const double origin[3], const double spacing[3],
    const double direction[9], const int extent[6]);

  /**
   * A reader's placement from its header: SplitAxisSteps, then
   * DescribeUnusableExtent with origin and extent. Returns "" on success,
   * else "the header's placement cannot be used: " and the reason.
   */
  static std::string PlaceAxisSteps(const double steps[9], const double origin[3],
    const int extent[6], double spacing[3], double direction[9]);

  /** Negates x and y of a point or vector given in RAS, making it LPS (and back). */
  static void FlipRightAnterior(double point[3]);

protected:
  vtkMCXPatientSpace() = default;
  ~vtkMCXPatientSpace() override = default;

private:
  vtkMCXPatientSpace(const vtkMCXPatientSpace&) = delete;
  void operator=(const vtkMCXPatientSpace&) = delete;
};

#endif
