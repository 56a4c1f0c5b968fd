#!/usr/bin/python3
"""Writes the VTI files the tests read (tests/ready/test_pattern.cpp):
one small Ready pattern in each encoding VTK's XML writer makes, with VTK's
own writer (Debian's python3-vtk9), and Ready's <RD> element put in after.

    /usr/bin/python3 tests/ready/vti/make_files.py

The grid is 8 x 6 with chemicals a and b:
    a[i] = 0.25 * i - 3,   b[i] = 1 / (i + 1),   i = x + 8 * y
(as Float32 or Float64), which the tests compute again.
"""
import os
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import numpy_to_vtk
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
W, H = 8, 6
RD = b"""
  <RD format_version="6">
    <description>A test pattern: two chemicals that diffuse.</description>
    <rule name="Test rule" type="formula" wrap="1">
      <param name="timestep">0.1</param>
      <param name="D">0.5</param>
      <formula number_of_chemicals="2">
        delta_a = D * laplacian_a;
        delta_b = D * laplacian_b;
      </formula>
    </rule>
    <initial_pattern_generator apply_when_loading="false" />
    <render_settings>
      <active_chemical value="b" />
      <low value="0" />
      <high value="1" />
    </render_settings>
  </RD>
"""


def write(name, dtype, mode, compressed, header64, encode=True):
    image = vtk.vtkImageData()
    image.SetDimensions(W, H, 1)
    i = np.arange(W * H, dtype=np.float64)
    for chem, values in (("a", 0.25 * i - 3), ("b", 1 / (i + 1))):
        array = numpy_to_vtk(values.astype(dtype), deep=True)
        array.SetName(chem)
        image.GetPointData().AddArray(array)
    writer = vtk.vtkXMLImageDataWriter()
    writer.SetInputData(image)
    path = os.path.join(HERE, name)
    writer.SetFileName(path)
    {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
     "appended": writer.SetDataModeToAppended}[mode]()
    writer.SetEncodeAppendedData(encode)
    if compressed:
        writer.SetCompressorTypeToZLib()
        writer.SetBlockSize(64)  # several blocks for 48 values
    else:
        writer.SetCompressorTypeToNone()
    writer.SetHeaderTypeToUInt64() if header64 else writer.SetHeaderTypeToUInt32()
    writer.Write()
    data = open(path, "rb").read()
    at = data.index(b">", data.index(b"<VTKFile")) + 1
    open(path, "wb").write(data[:at] + RD + data[at:])


write("ascii-f32.vti", np.float32, "ascii", False, False)
write("binary-f32.vti", np.float32, "binary", False, False)
write("binary-zlib-f64.vti", np.float64, "binary", True, True)
write("binary-zlib-f32-uint32.vti", np.float32, "binary", True, False)
write("appended-base64-f32.vti", np.float32, "appended", False, True)
write("appended-base64-zlib-f64.vti", np.float64, "appended", True, False)
write("appended-raw-f64.vti", np.float64, "appended", False, True, encode=False)
write("appended-raw-zlib-f32.vti", np.float32, "appended", True, True, encode=False)
