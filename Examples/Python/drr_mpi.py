#!/usr/bin/env python3
"""A DRR on MPI with mpi4py: each process reads and indexes its z-slab only.

    mpirun -np 4 python3 drr_mpi.py [VOLUME.vti] [--output PREFIX] [--samples N]

The processes add their exact sums: process 0's output is the image of a
single process, bit for bit, for any process count (the others' are empty);
it writes PREFIX.npy (float64 line integrals, row 0 at the bottom).
"""
import argparse
import os

from mpi4py import MPI  # starts MPI before VTK's controller takes it over
import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController

import mcxray

BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "Data", "ct_head_headsq.vti")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("volume", nargs="?", default=BUNDLED)
    parser.add_argument("--output", default="drr_mpi")
    parser.add_argument("--samples", type=int, default=2**22 - 1)
    args = parser.parse_args()

    controller = vtkMPIController()
    controller.Initialize()  # MPI is already running (mpi4py)
    vtkMultiProcessController.SetGlobalController(controller)  # the filters' default

    reader = vtkXMLImageDataReader()  # reads only the slab asked of it
    reader.SetFileName(args.volume)
    index = mcxray.vtkMCXDensityIndex()
    index.SetInputConnection(reader.GetOutputPort())
    tf = vtkPiecewiseFunction()
    tf.AddPoint(500, 0.0)
    tf.AddPoint(3000, 1.0)
    projector = mcxray.vtkMCXProjector()
    projector.SetInputConnection(index.GetOutputPort())
    projector.SetTransferFunction(tf)
    projector.SetDepositToFootprint()
    projector.SetNumberOfSamples(args.samples)
    projector.SetImageSize(256, 256)
    projector.Update()

    image = projector.GetOutput()  # process 0's; the others' are empty
    if MPI.COMM_WORLD.rank == 0:
        values = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(256, 256)
        numpy.save(args.output + ".npy", values)
        fields = image.GetFieldData()
        print("%d processes, %d samples, estimated relative error %.4g, sum %.17g, wrote %s.npy" % (
            MPI.COMM_WORLD.size, fields.GetArray("SampleCount").GetTuple1(0),
            fields.GetArray("EstimatedRelativeError").GetTuple1(0), values.sum(), args.output))


if __name__ == "__main__":
    main()
