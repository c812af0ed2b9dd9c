#!/usr/bin/env python3
"""A digitally reconstructed radiograph (DRR) of a real CT, to PNG and NumPy.

    python3 drr.py [VOLUME] [--output PREFIX] [--samples N] [--size N]

VOLUME is a .vti, .nii/.nii.gz, .nrrd/.nhdr or .mha/.mhd CT, or a folder with
one DICOM series (read with vtk-dicom, in Hounsfield units; default: the
bundled CT head), placed in DICOM patient space (LPS) whatever the format. Writes
PREFIX.png (windowed 0..maximum) and PREFIX.npy (float64 line integrals of
the TF, in TF units times mm, row 0 at the bottom), and prints what it made.
"""
import argparse
import os
import sys
import time

import numpy
from vtkmodules.vtkImagingCore import vtkImageShiftScale
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction

import mcxray
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand

BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "Data", "ct_head_headsq.vti")


def first_error(algorithm, run):
    """Runs run(); the algorithm's first error, kept instead of printed, or None."""
    errors = []

    def keep(caller, event, report=None):
        errors.append(mcxray.vtkMCXFirstErrorObserver.MessageOf(report))
    keep.CallDataType = VTK_STRING  # VTK hands the report over
    algorithm.AddObserver(vtkCommand.ErrorEvent, keep)
    algorithm.GetExecutive().AddObserver(vtkCommand.ErrorEvent, keep)  # its "returned failure"
    run()
    return errors[0] if errors else None


def read_with(reader):
    """Updates the reader; its first error ends the script in one line (nothing is written)."""
    error = first_error(reader, reader.Update)
    if error:
        sys.exit("drr.py: error: %s" % error)
    volume = reader.GetOutput()
    if volume.GetNumberOfPoints() == 0:
        sys.exit("drr.py: error: no voxels read")
    return volume


def read_volume(path):
    if os.path.isdir(path):
        reader = mcxray.vtkMCXDICOMSeriesReader()
        reader.SetDirectoryName(path)
        return read_with(reader)
    if path.endswith(".vti"):
        reader = vtkXMLImageDataReader()
    elif path.endswith(".nii") or path.endswith(".nii.gz"):
        reader = mcxray.vtkMCXNIFTIReader()  # patient space (LPS) from the sform or qform, scl_slope applied
    elif path.endswith(".nrrd") or path.endswith(".nhdr"):
        reader = mcxray.vtkMCXNrrdReader()  # patient space from the space directions and origin
    elif path.endswith(".mha") or path.endswith(".mhd"):
        reader = mcxray.vtkMCXMetaImageReader()  # patient space from TransformMatrix and Offset
    else:
        sys.exit("drr.py: error: expected a .vti, .nii/.nii.gz, .nrrd/.nhdr or .mha/.mhd volume or a "
                 "DICOM folder, not %r" % path)
    if not os.path.isfile(path):
        sys.exit("drr.py: error: no such file %r" % path)
    reader.SetFileName(path)
    return read_with(reader)


def check_output(prefix):
    """Ends the script in one line, before any work, where PREFIX.png or PREFIX.npy cannot be written."""
    folder = os.path.dirname(os.path.abspath(prefix))
    if not os.path.isdir(folder):
        sys.exit("drr.py: error: no folder %r for --output %r" % (folder, prefix))
    for path in (prefix + ".png", prefix + ".npy"):
        if os.path.isdir(path):
            sys.exit("drr.py: error: cannot write %r: it is a directory" % path)


def write_outputs(prefix, image, values):
    """PREFIX.png and PREFIX.npy, both or neither: each written under a temporary name, renamed
    once both are complete (an existing file is replaced only then)."""
    png, npy = prefix + ".png", prefix + ".npy"
    parts = [png + ".part", npy + ".part"]
    try:
        with open(parts[1], "wb") as f:
            numpy.save(f, values)
        window = vtkImageShiftScale()
        window.SetInputData(image)
        window.SetScale(255.0 / values.max() if values.max() > 0 else 1.0)
        window.SetOutputScalarTypeToUnsignedChar()
        window.ClampOverflowOn()
        writer = vtkPNGWriter()
        writer.SetInputConnection(window.GetOutputPort())
        writer.SetFileName(parts[0])
        error = first_error(writer, writer.Write)
        if error or writer.GetErrorCode():
            raise OSError(error or "the PNG writer failed (error code %d)" % writer.GetErrorCode())
        os.replace(parts[1], npy)
        os.replace(parts[0], png)
    except OSError as error:
        for part in parts:
            if os.path.exists(part):
                os.remove(part)
        sys.exit("drr.py: error: cannot write %s and %s: %s" % (png, npy, error))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("volume", nargs="?", default=BUNDLED)
    parser.add_argument("--output", default="drr")
    parser.add_argument("--samples", type=int, default=(1 << 20) - 1)
    parser.add_argument("--size", type=int, default=256)
    args = parser.parse_args()

    check_output(args.output)
    volume = read_volume(args.volume)
    low, high = volume.GetScalarRange()
    # Denser tissue weighs more: 0 at the darkest third of the range, rising to 1 at the top.
    tf = vtkPiecewiseFunction()
    tf.AddPoint(low + (high - low) / 3.0, 0.0)
    tf.AddPoint(high, 1.0)

    start = time.perf_counter()
    index = mcxray.vtkMCXDensityIndex()
    index.SetInputData(volume)
    projector = mcxray.vtkMCXProjector()
    projector.SetInputConnection(index.GetOutputPort())
    projector.SetTransferFunction(tf)
    projector.SetDeposit(mcxray.vtkMCXTypes.FOOTPRINT)  # far less error per sample than POINT
    projector.SetNumberOfSamples(args.samples)
    projector.SetDetectorAxisU(1, 0, 0)  # a frontal view along +y, z up
    projector.SetDetectorAxisV(0, 0, 1)
    projector.SetImageSize(args.size, args.size)
    projector.Update()
    seconds = time.perf_counter() - start
    image = projector.GetOutput()

    values = mcxray.image_to_numpy(image)
    write_outputs(args.output, image, values)

    fd = image.GetFieldData()
    spacing = image.GetSpacing()
    print("volume:    %s %s" % (args.volume, volume.GetDimensions()))
    print("image:     %s, %.3f mm pixels, line integrals %.4g .. %.4g" % (values.shape, spacing[0], values.min(), values.max()))
    print("samples:   %d in %.3f s, estimated relative error %.4f" % (
        fd.GetArray("SampleCount").GetTuple1(0), seconds, fd.GetArray("EstimatedRelativeError").GetTuple1(0)))
    integral = fd.GetArray("Integral").GetTuple1(0)
    # The image covers the volume, so its values times the pixel area add up to the TF-weighted integral.
    print("integral:  %.6g; image sum x pixel area / integral = %.6f" % (
        integral, values.sum() * spacing[0] * spacing[1] / integral if integral > 0 else float("nan")))
    print("wrote:     %s.png %s.npy" % (args.output, args.output))


if __name__ == "__main__":
    main()
