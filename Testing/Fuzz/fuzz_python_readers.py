"""The fuzzing stage's harness for the Python readers: mutated volume files
through every reader class the Python package and the ParaView plugin offer
(vtkMCXVolumeReader, and the format reader of the file's extension), in a
worker process under an address-space limit, as a script would call them.

    python3 fuzz_python_readers.py --seed 1 --runs 400 --work DIR [--dicom SERIES] CORPUS_DIR...

First every seed is read as it is (the Regressions/PythonReaders folder
holds what this harness found), then each input is a seed of the libFuzzer corpus (Corpus/VolumeHeader: the first
byte picks the extension, as FuzzVolumeHeader.cxx reads it) or a whole file
of another folder (its own extension; a .dcm file is a DICOM slice, read
as a folder of its own by vtkMCXDICOMSeriesReader and vtkMCXVolumeReader;
--dicom adds three slices of a series), mutated 1 to 3 times with a fixed
random seed: bits flipped, bytes set to boundary values, numbers replaced by
boundary numbers, the letter case of a key changed, lines repeated or
dropped, the file cut short or a run of bytes inserted. A reader may read a
mutated file or refuse it; what it may not do is end the interpreter (a
crash, an uncaught bad_alloc under the address-space limit), run past the
time limit, report a multi-line error or one that is no printable UTF-8, or hand back a volume
whose scalars do not fill its extent. Each such input is kept in WORK with
what it did; the exit status is 1 when there is any.
"""
import argparse
import os
import random
import re
import select
import subprocess
import sys
import time

EXTENSIONS = [".nii", ".nii.gz", ".mha", ".mhd", ".nrrd", ".nhdr", ".vtk", ".slc", ".vti"]
OWN_EXTENSIONS = EXTENSIONS + [".dcm"]
FORMAT_READERS = {".nii": "vtkMCXNIFTIReader", ".nii.gz": "vtkMCXNIFTIReader",
                  ".mha": "vtkMCXMetaImageReader", ".mhd": "vtkMCXMetaImageReader",
                  ".nrrd": "vtkMCXNrrdReader", ".nhdr": "vtkMCXNrrdReader",
                  ".dcm": "vtkMCXDICOMSeriesReader"}
BOUNDARY_BYTES = [0x00, 0xFF, 0x7F, 0x80, 0x0A, 0x25, 0x3D, 0x3A, 0x3C]
BOUNDARY_NUMBERS = [b"0", b"-1", b"1", b"2147483647", b"2147483648", b"4294967296",
                    b"9223372036854775807", b"-2147483648", b"1e308", b"nan"]
NUMBER = re.compile(rb"-?\d+(\.\d+)?")
WORD = re.compile(rb"[A-Za-z_]{3,}")
ADDRESS_SPACE = 6 << 30   # the worker's limit: an allocation past it raises
MEMORY_BUDGET = 1 << 30   # vtkMCXVolumeReader's budget for the claimed voxels

# The worker: reads one path per line from stdin, answers one line per path.
WORKER = r'''
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, (%d, %d))
import mcxray
FORMAT_READERS = %r
def read(reader):
    errors = mcxray.vtkMCXFirstErrorObserver()
    errors.ObserveAlgorithm(reader)
    reader.Update()
    errors.StopObserving()
    text = errors.GetErrorText()
    if isinstance(text, bytes):  # VTK hands back what is no UTF-8 as bytes
        return "UNPRINTABLE ERROR " + repr(text)
    image = reader.GetOutput()
    points = image.GetNumberOfPoints() if image else 0
    scalars = image.GetPointData().GetScalars() if points else None
    if text:
        return "refused" if "\n" not in text.strip() else "MULTI-LINE ERROR " + repr(text)
    if points == 0 or scalars is None:
        return "NO VOLUME AND NO ERROR"
    if scalars.GetNumberOfTuples() != points:
        return "SCALARS %%d FOR %%d POINTS" %% (scalars.GetNumberOfTuples(), points)
    return "read"
for line in sys.stdin:
    path, extension = line.rstrip("\n").split("\t")
    results = []
    if extension == ".dcm":  # a slice in a folder of its own: the folder is read
        path = path.rsplit("/", 1)[0]
    checked = mcxray.vtkMCXVolumeReader()
    checked.SetFileName(path)
    checked.SetMemoryBudget(%d)
    results.append("vtkMCXVolumeReader: " + read(checked))
    if extension in FORMAT_READERS:
        reader = getattr(mcxray, FORMAT_READERS[extension])()
        if extension == ".dcm":
            reader.SetDirectoryName(path)
        else:
            reader.SetFileName(path)
        results.append(FORMAT_READERS[extension] + ": " + read(reader))
    print("; ".join(results), flush=True)
''' % (ADDRESS_SPACE, ADDRESS_SPACE, FORMAT_READERS, MEMORY_BUDGET)


def seeds_of(folders):
    """(bytes, extension) of every seed: corpus files carry their extension
    in the first byte, other files in their name."""
    seeds = []
    for folder in folders:
        for name in sorted(os.listdir(folder)):
            path = os.path.join(folder, name)
            if not os.path.isfile(path) or name.endswith(".md"):
                continue
            data = open(path, "rb").read()
            extension = next((e for e in OWN_EXTENSIONS if name.lower().endswith(e)), None)
            if extension is None and data:
                seeds.append((data[1:], EXTENSIONS[data[0] % len(EXTENSIONS)]))
            elif extension is not None:
                seeds.append((data, extension))
    return seeds


def mutate(data, rng):
    """data changed once, in one of the ways the module docstring lists."""
    data = bytearray(data) or bytearray(b"\n")
    kind = rng.randrange(8)
    at = rng.randrange(len(data))
    if kind == 0:
        data[at] ^= 1 << rng.randrange(8)
    elif kind == 1:
        data[at] = rng.choice(BOUNDARY_BYTES)
    elif kind == 2:
        numbers = list(NUMBER.finditer(data))
        if numbers:
            m = rng.choice(numbers)
            data[m.start():m.end()] = rng.choice(BOUNDARY_NUMBERS)
    elif kind == 3:
        words = list(WORD.finditer(data))
        if words:
            m = rng.choice(words)
            data[m.start():m.end()] = rng.choice([bytes(m.group()).lower(), bytes(m.group()).upper()])
    elif kind == 4:
        lines = bytes(data).split(b"\n")
        line = rng.randrange(len(lines))
        lines.insert(line, lines[line]) if rng.random() < 0.5 else lines.pop(line)
        data = bytearray(b"\n".join(lines))
    elif kind == 5:
        del data[at:]
    elif kind == 6:
        data[at:at] = bytes([rng.randrange(256)]) * rng.choice([1, 8, 300, 70000])
    else:
        del data[at:at + rng.randrange(1, 64)]
    return bytes(data)


class Worker:
    """The reading process; started again after it dies."""

    def __init__(self, log):
        self.process = None
        self.log = log  # the worker's stderr: a pipe nobody reads could fill and block it

    def ask(self, path, extension, timeout):
        """The worker's answer for path, or what ended it."""
        if self.process is None or self.process.poll() is not None:
            with open(self.log, "ab") as log:  # kept whole: a crash's traceback stays there
                self.process = subprocess.Popen([sys.executable, "-X", "faulthandler", "-c", WORKER], stdin=subprocess.PIPE,
                                                stdout=subprocess.PIPE, stderr=log, text=True,
                                                errors="backslashreplace")
        self.process.stdin.write(path + "\t" + extension + "\n")
        self.process.stdin.flush()
        ready, _, _ = select.select([self.process.stdout], [], [], timeout)
        if not ready:
            self.process.kill()
            self.process.wait()
            return "HUNG past %g s" % timeout
        answer = self.process.stdout.readline()
        if not answer:
            code = self.process.wait()
            with open(self.log, "rb") as log:
                log.seek(max(0, os.path.getsize(self.log) - 4096))
                tail = log.read().decode(errors="backslashreplace").strip().splitlines()[-1:]
            return "INTERPRETER ENDED (status %d%s)" % (code, ": " + tail[0] if tail else "")
        return answer.strip()

    def close(self):
        if self.process and self.process.poll() is None:
            self.process.stdin.close()
            self.process.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("corpus", nargs="+", help="seed folders")
    parser.add_argument("--dicom", help="a DICOM series folder: three of its slices are seeds too")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--runs", type=int, default=400)
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per input")
    parser.add_argument("--work", required=True, help="folder for inputs and findings")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rng = random.Random(args.seed)
    seeds = seeds_of(args.corpus)
    if args.dicom and os.path.isdir(args.dicom):
        slices = sorted(n for n in os.listdir(args.dicom) if not n.startswith("."))[:3]
        seeds += [(open(os.path.join(args.dicom, n), "rb").read(), ".dcm") for n in slices]
    os.makedirs(os.path.join(args.work, "dicom"), exist_ok=True)
    worker = Worker(os.path.join(args.work, "worker.log"))
    findings = []
    outcomes = {}
    start = time.time()
    for run in range(len(seeds) + args.runs):
        if run < len(seeds):
            data, extension = seeds[run]
        else:
            data, extension = rng.choice(seeds)
            for _ in range(rng.randrange(1, 4)):
                data = mutate(data, rng)
        path = os.path.join(args.work, "dicom" if extension == ".dcm" else "", "input" + extension)
        with open(path, "wb") as f:
            f.write(data)
        answer = worker.ask(path, extension, args.timeout)
        for part in answer.split("; "):
            outcome = part.split(": ", 1)[-1]
            outcomes[outcome if outcome in ("read", "refused") else "finding"] = \
                outcomes.get(outcome if outcome in ("read", "refused") else "finding", 0) + 1
        if any(word in answer for word in ("HUNG", "ENDED", "MULTI-LINE", "UNPRINTABLE", "NO VOLUME", "SCALARS")):
            kept = os.path.join(args.work, "finding-%04d%s" % (run, extension))
            os.replace(path, kept)
            findings.append("%s: %s" % (kept, answer))
    worker.close()
    print("%d inputs from %d seeds in %.0f s: %s" % (len(seeds) + args.runs, len(seeds), time.time() - start,
                                                    ", ".join("%s %d" % kv for kv in sorted(outcomes.items()))))
    for finding in findings:
        print("FINDING " + finding)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
