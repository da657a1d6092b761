// Shared by the GUI tests (tst_ui_main_window, tst_review): what every test that shows the
// workstation's 3-D view needs before its first window. (Not named ui_*.h: AUTOUIC takes
// such includes for generated forms.)
#pragma once

#include <QSurfaceFormat>

namespace palpation::test {

/// The default OpenGL format the VTK view needs: a 3.2 core context with depth and stencil
/// (interlaced stereo uses the stencil), as ui/main.cpp sets it. Call before the first
/// window is created.
inline void use_vtk_surface_format() {
  QSurfaceFormat fmt;
  fmt.setRenderableType(QSurfaceFormat::OpenGL);
  fmt.setVersion(3, 2);
  fmt.setProfile(QSurfaceFormat::CoreProfile);
  fmt.setDepthBufferSize(24);
  fmt.setStencilBufferSize(8);
  QSurfaceFormat::setDefaultFormat(fmt);
}

}  // namespace palpation::test
