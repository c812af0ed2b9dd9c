"""What the geometry tests share (test_geometry.py, test_geometry_files.py):
an axis-aligned MetaImage phantom, the slices of a rendered stack with row 0
at the top (as projection matrices count rows), matrices compared up to
scale."""
import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def write_metaimage(path, hu, spacing, origin=(0, 0, 0)):
    """hu (z, y, x) as 16-bit voxels of `spacing` mm from `origin`, no turn."""
    dims = hu.shape[::-1]
    with open(path, "wb") as f:
        f.write(("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                 "TransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = %r %r %r\n"
                 "ElementSpacing = %g %g %g\nDimSize = %d %d %d\nElementType = MET_SHORT\n"
                 "ElementDataFile = LOCAL\n"
                 % (tuple(float(x) for x in origin) + (spacing,) * 3 + tuple(dims))).encode())
        f.write(hu.astype("<i2").tobytes())


def read_stack(path):
    """The slices of a .vti (N, rows, columns; its active scalars), row 0 at the top, and its
    ProjectionMatrix field as (N, 3, 4)."""
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    dims = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetScalars())  # LineIntegral, or the physics'
    matrices = vtk_to_numpy(image.GetFieldData().GetArray("ProjectionMatrix")).reshape(-1, 3, 4)
    return values.reshape(dims[2], dims[1], dims[0])[:, ::-1, :], matrices


def read_arrays(path):
    """Every point array of a .vti (as read_stack's slices) and every field array, by name."""
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    dims = image.GetDimensions()
    points, fields = image.GetPointData(), image.GetFieldData()
    return ({points.GetArrayName(i): vtk_to_numpy(points.GetArray(i)).reshape(dims[2], dims[1], dims[0])[:, ::-1, :]
             for i in range(points.GetNumberOfArrays())},
            {fields.GetArrayName(i): vtk_to_numpy(fields.GetArray(i)) for i in range(fields.GetNumberOfArrays())})


def normalized(matrix):
    matrix = numpy.asarray(matrix, float)
    return matrix / numpy.linalg.norm(matrix)
