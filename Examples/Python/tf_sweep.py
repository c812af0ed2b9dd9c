#!/usr/bin/env python3
"""Sweeps a transfer function over a CT and times each update, as a user
editing the TF would see it: the index is built once, each TF change
re-samples the stored point cloud and re-projects it.

    python3 tf_sweep.py [VOLUME.vti] [--steps N] [--samples N] [--size N]
"""
import argparse
import os
import time

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import mcxray

BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "Data", "ct_head_headsq.vti")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("volume", nargs="?", default=BUNDLED)
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--samples", type=int, default=(1 << 22) - 1)
    parser.add_argument("--size", type=int, default=256)
    args = parser.parse_args()

    reader = vtkXMLImageDataReader()
    reader.SetFileName(args.volume)
    start = time.perf_counter()
    index = mcxray.vtkMCXDensityIndex()
    index.SetInputConnection(reader.GetOutputPort())
    index.Update()
    low, high = reader.GetOutput().GetScalarRange()
    print("index: %.3f s (read included)" % (time.perf_counter() - start))

    tf = vtkPiecewiseFunction()
    sampler = mcxray.vtkMCXPointSampler()
    sampler.SetInputConnection(index.GetOutputPort())
    sampler.SetTransferFunction(tf)
    sampler.SetNumberOfSamples(args.samples)
    sampler.ReusePointsOn()  # nothing here keeps an old cloud: refill it in place
    projector = mcxray.vtkMCXProjector()
    projector.SetInputConnection(sampler.GetOutputPort())
    projector.SetImageSize(args.size, args.size)

    width = (high - low) / 4.0
    print("%10s %12s %10s %12s" % ("centre", "samples", "update s", "mean"))
    for step in range(args.steps):
        centre = low + width / 2.0 + step * (high - low - width) / max(1, args.steps - 1)
        tf.RemoveAllPoints()
        tf.AddPoint(centre - width / 2.0, 0.0)
        tf.AddPoint(centre + width / 2.0, 1.0)
        start = time.perf_counter()
        projector.Update()
        seconds = time.perf_counter() - start
        values = mcxray.image_to_numpy(projector.GetOutput())
        print("%10.1f %12d %10.4f %12.5g" % (centre, sampler.GetOutput().GetNumberOfPoints(), seconds, values.mean()))


if __name__ == "__main__":
    main()
