// The peers BenchmarkPeers times against ours, in the same cone-beam
// geometry: plastimatch drr (a process) and VTK's GPU ray-cast mapper.
#ifndef mcxPeerRuns_h
#define mcxPeerRuns_h

#include <string>

class vtkCamera;
class vtkImageData;
class vtkPiecewiseFunction;

namespace mcxbench
{
/// The cone beam of both tools: source to isocentre, source to detector and
/// the detector's side, in mm.
struct ConeBeam
{
  double SourceToIsocentre = 1000;
  double SourceToDetector = 1500;
  double DetectorSize = 600;
};

/// plastimatch drr -i exact: its own render time ("Total time: ... secs",
/// after loading) and the whole process's, medians of 3, and its error.
struct PeerRun
{
  double RenderSeconds = 0;
  double ProcessSeconds = 0;
  double Error = 1;
  bool Done = false;
};

/// plastimatch on the MetaImage mha, isocentre iso, size^2 pixels, its
/// files under output (removed after); Done false, the command printed, on
/// failure.
PeerRun RunPlastimatch(const std::string& mha, const std::string& output, const double iso[3],
  int size, const ConeBeam& beam, vtkImageData* reference);

/// VTK's GPU ray-cast mapper in additive blend mode (software GL under Xvfb
/// here): an 8-bit, clamped sum of the opacity along each ray. The opacity TF
/// is our TF scaled down until nothing saturates; one least-squares gain then
/// maps the grey levels to line integrals. False without a display.
bool RenderWithVTK(vtkImageData* volume, vtkPiecewiseFunction* tf, vtkCamera* camera, int size,
  vtkImageData* reference, double& seconds, double& error);
}

#endif
