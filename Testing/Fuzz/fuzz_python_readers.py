"""Mutation fuzzing of the Python readers (issue 39): seeds of the binary
formats mutated (bytes flipped, words set to boundary values, pieces cut,
repeated or dropped), each read in a fresh Python under an address-space
limit and a time limit by the reader ParaView and Python users call:
vtkMCXVolumeReader (.vti, in this process; .slc in its child process),
vtkMCXNIFTIReader (.nii) and vtkMCXDICOMSeriesReader (a folder of slices).

    python3 fuzz_python_readers.py [--cases N] [--seed S] [--dicom FOLDER] [--keep DIR]

Each case must end with the interpreter alive (no signal, no uncaught
bad_alloc), within the time limit, with at most one VTK error line, and no
volume where there is an error. Failing inputs are kept in --keep; the exit
status is the number of failures (capped at 100).
"""
import argparse
import os
import random
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "Corpus", "VolumeHeader")
HOSTILE = os.path.join(HERE, "..", "Data", "Hostile")
OWN = os.path.join(HERE, "Corpus", "PythonReaders")  # encapsulated DICOM (RLE)
WORDS = [0, 1, 0x7F, 0xFF, 0x7FFF, 0xFFFF, 0x7FFFFFFF, 0xFFFFFFFF, 0x80000000]

READ = """
import resource, sys
import mcxray
pages = int(open('/proc/self/statm').read().split()[0])
room = pages * resource.getpagesize() + 1024 * 2**20
resource.setrlimit(resource.RLIMIT_AS, (room, room))
kind, path = sys.argv[1], sys.argv[2]
if kind == 'dicom':
    reader = mcxray.vtkMCXDICOMSeriesReader()
    reader.SetDirectoryName(path)
elif kind == 'nifti':
    reader = mcxray.vtkMCXNIFTIReader()
    reader.SetFileName(path)
else:
    reader = mcxray.vtkMCXVolumeReader()
    reader.SetFileName(path)
    reader.SetReadInChildProcess(kind == 'contained')
    reader.SetTimeLimit(20)
reader.Update()
print('points', reader.GetOutput().GetNumberOfPoints())
"""


def seeds(dicom):
    """(kind, extension, bytes) of each seed."""
    found = []
    for name in sorted(os.listdir(CORPUS)):
        with open(os.path.join(CORPUS, name), "rb") as f:
            data = f.read()[1:]  # the first byte picks the C++ harness's extension
        if name.startswith("vti"):
            found.append(("volume", ".vti", data))
        elif name == "nifti":
            found.append(("nifti", ".nii", data))
        elif name == "slc":
            found.append(("contained", ".slc", data))
    for name in sorted(os.listdir(HOSTILE)):
        if name.endswith(".vti"):
            with open(os.path.join(HOSTILE, name), "rb") as f:
                found.append(("volume", ".vti", f.read()))
    for name in sorted(os.listdir(OWN)):
        with open(os.path.join(OWN, name), "rb") as f:
            found.append(("dicom", ".dcm", f.read()))
    if dicom and os.path.isdir(dicom):
        slices = sorted(n for n in os.listdir(dicom) if not n.startswith("."))[:3]
        for name in slices:
            with open(os.path.join(dicom, name), "rb") as f:
                found.append(("dicom", ".dcm", f.read()))
    return found


def mutate(data, rng):
    data = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        if not data:
            data = bytearray(b"\0")
        at = rng.randrange(len(data))
        choice = rng.randrange(6)
        if choice == 0:
            data[at] = rng.randrange(256)
        elif choice == 1 and at + 4 <= len(data):
            data[at:at + 4] = rng.choice(WORDS).to_bytes(4, "little")
        elif choice == 2:
            del data[at:at + rng.randint(1, 64)]
        elif choice == 3:
            data[at:at] = data[at:at + rng.randint(1, 256)]
        elif choice == 4:
            data = data[:at]
        else:  # a decimal number made huge (text headers)
            digits = at
            while digits < len(data) and chr(data[digits]).isdigit():
                digits += 1
            data[at:digits] = str(rng.choice([2**31 - 1, 2**32, 2**63, 10**20])).encode()
    return bytes(data)


def run_case(kind, path):
    """The case's failure in words, or None."""
    try:
        result = subprocess.run([sys.executable, "-c", READ, kind, path],
                                capture_output=True, text=True, errors="replace", timeout=60)
    except subprocess.TimeoutExpired:
        return "no answer within 60 s"
    errors = [line for line in result.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]
    if result.returncode != 0:
        return "the interpreter ended with status %d: %s" % (
            result.returncode, (result.stderr.strip().splitlines() or [""])[-1][:200])
    if len(errors) > 1:
        return "%d error lines: %s" % (len(errors), " | ".join(errors)[:300])
    if errors and "points 0" not in result.stdout:
        return "an error and a volume: " + errors[0][:200]
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--dicom", default="")
    parser.add_argument("--keep", default="")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    pool = seeds(args.dicom)
    work = tempfile.mkdtemp(prefix="mcxray-fuzz-py-")
    failures = 0
    try:
        for case in range(args.cases):
            kind, extension, data = rng.choice(pool)
            mutated = mutate(data, rng)
            if kind == "dicom":
                path = os.path.join(work, "series-%d" % case)
                os.mkdir(path)
                with open(os.path.join(path, "image" + extension), "wb") as f:
                    f.write(mutated)
            else:
                path = os.path.join(work, "case-%d%s" % (case, extension))
                with open(path, "wb") as f:
                    f.write(mutated)
            problem = run_case(kind, path)
            if problem:
                failures += 1
                print("case %d (%s%s): %s" % (case, kind, extension, problem))
                if args.keep:
                    os.makedirs(args.keep, exist_ok=True)
                    target = os.path.join(args.keep, os.path.basename(path))
                    (shutil.copytree if os.path.isdir(path) else shutil.copy)(path, target)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
    finally:
        shutil.rmtree(work)
    print("%d cases, %d failures" % (args.cases, failures))
    return min(failures, 100)


if __name__ == "__main__":
    sys.exit(main())
