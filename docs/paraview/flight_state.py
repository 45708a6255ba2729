"""Build docs/paraview/flight.pvsm: the ParaView state of docs/paraview.md, saved by ParaView.

Run with ParaView's batch interpreter (it needs a display; headless: ``xvfb-run -a``):

    fem-tether simulate --length 500 --out results_sim
    xvfb-run -a pvbatch docs/paraview/flight_state.py results_sim/fe_L500 docs/paraview/flight.pvsm \
        docs/figures/paraview-flight.png

It opens the line (``tether.pvd``) and the kite's track (``tether_kite_track.vtu``) of one
``simulate --out`` run, colours the line by ``tension_N``, marks the winch and the kite
(spheres at the line's first and last node), writes the time, and lays out two views:
the side view (x downwind to the right, z up) and the view from downwind (y to the right).
The saved state names the files relative to the run's folder ``fe_L500``; load it with
"Search files under specified directory" (docs/paraview.md).  Given a third argument, the
script then loads the saved state as a user would (a new session, the files searched in
the run's folder) and saves a screenshot of its layout there, at the last time step.
"""

import sys
from pathlib import Path

from paraview.simple import (AnnotateTimeFilter, AssignViewToLayout, ColorBy, CreateLayout, CreateView,
                             GetAnimationScene, GetColorTransferFunction, GetLayoutByName, GetScalarBar, Glyph, LoadState,
                             PVDReader, ResetSession, SaveScreenshot, SaveState, Show,
                             XMLUnstructuredGridReader)

folder, state = Path(sys.argv[1]).resolve(), Path(sys.argv[2])
line = PVDReader(registrationName="tether.pvd", FileName=str(folder / "tether.pvd"))
track = XMLUnstructuredGridReader(registrationName="tether_kite_track.vtu",
                                  FileName=[str(folder / "tether_kite_track.vtu")])
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
line.UpdatePipeline(line.TimestepValues[0])
nodes = line.GetDataInformation().GetNumberOfPoints()
ends = Glyph(registrationName="winch and kite", Input=line, GlyphType="Sphere")
ends.ScaleArray = ["POINTS", "No scale array"]
ends.ScaleFactor = 10.0
ends.GlyphMode = "Every Nth Point"
ends.Stride = nodes - 1                  # the first node (the winch) and the last (the kite)
clock = AnnotateTimeFilter(registrationName="time", Input=line, Format="t = {time:.2f} s")

tension = GetColorTransferFunction("tension_N")
tension.ApplyPreset("Plasma (matplotlib)", True)
layout = CreateLayout("flight")
for cell, (name, position, up) in enumerate((("side", (250.0, -1500.0, 300.0), (0.0, 0.0, 1.0)),
                                             ("downwind", (2500.0, 0.0, 300.0), (0.0, 0.0, 1.0)))):
    view = CreateView("RenderView")
    view.ViewSize = [640, 560]
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    AssignViewToLayout(view=view, layout=layout, hint=cell + 1)
    shown = Show(line, view)
    shown.LineWidth = 3.0
    ColorBy(shown, ("CELLS", "tension_N"))
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(tension, view)
    bar.Title, bar.ComponentTitle = "tension_N", "[N]"
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.RangeLabelFormat = "%.0f"
    view.OrientationAxesLabelColor = [0.0, 0.0, 0.0]
    path = Show(track, view)
    path.AmbientColor = path.DiffuseColor = [0.45, 0.45, 0.45]
    ColorBy(path, ("POINTS", None))
    marks = Show(ends, view)
    ColorBy(marks, ("POINTS", None))
    marks.AmbientColor = marks.DiffuseColor = [0.1, 0.6, 0.8]
    text = Show(clock, view)
    text.Color = [0.0, 0.0, 0.0]
    view.CameraPosition = list(position)
    view.CameraFocalPoint = [250.0, 0.0, 300.0] if name == "side" else [0.0, 0.0, 300.0]
    view.CameraViewUp = list(up)
    view.CameraParallelProjection = 1
    view.ResetCamera(False)
tension.RescaleTransferFunction(149900.0, 150100.0)
scene.AnimationTime = line.TimestepValues[-1]
SaveState(str(state))
text = state.read_text()
state.write_text(text.replace(str(folder) + "/", ""))       # file names relative to the run's folder

if len(sys.argv) > 3:
    ResetSession()
    LoadState(str(state), data_directory=str(folder))
    GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    SaveScreenshot(sys.argv[3], GetLayoutByName("flight"), ImageResolution=[1280, 560])
