// The OpenGL side of vtkMCXXRayMapper, the only part of it that talks to the
// GPU: it reads the depth buffer of the opaque geometry drawn so far, and
// shows an image of line integrals through a window and level, as film or as
// additive light. The projection itself runs on the CPU (the mapper).
#ifndef vtkMCXXRayDisplayPrivate_h
#define vtkMCXXRayDisplayPrivate_h

#include "vtkSmartPointer.h"

#include <memory>
#include <vector>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class vtkMCXXRayDisplay
{
public:
  vtkMCXXRayDisplay();
  ~vtkMCXXRayDisplay();
  vtkMCXXRayDisplay(const vtkMCXXRayDisplay&) = delete;
  vtkMCXXRayDisplay& operator=(const vtkMCXXRayDisplay&) = delete;

  /// The depth buffer of the viewport (origin x0, y0) as drawn so far.
  static std::vector<float> ReadDepth(
    vtkOpenGLRenderWindow* window, int x0, int y0, int width, int height);

  /// Whether an uploaded image lives in this window's context.
  bool HasImageIn(vtkOpenGLRenderWindow* window) const;

  /// Uploads width x height line integrals (rows from the bottom) as the
  /// image to show.
  void Upload(vtkOpenGLRenderWindow* window, int width, int height, const float* values);

  /// How the image meets what the renderer drew before it.
  struct Blending
  {
    bool Invert = false;            // show 1 - g
    bool Film = false;              // opaque where nothing opaque was drawn
    bool OverGeometry = false;      // opaque geometry was drawn: blend over it too
    bool CompositedByDepth = false; // write a depth for a depth compositor
  };

  /// Draws the image over the viewport, g = (value - lowest) * inverseWindow
  /// clamped to [0, 1]; false if the display shader cannot be built.
  bool Draw(
    vtkOpenGLRenderWindow* window, double lowest, double inverseWindow, const Blending& blending);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  /// The display shader, built on first use; false if it cannot be.
  bool ReadyShader(vtkOpenGLRenderWindow* window);

  vtkSmartPointer<vtkTextureObject> Texture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
};

#endif
