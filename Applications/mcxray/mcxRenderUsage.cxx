// The text of mcxray render --help (also the tool's main help), apart from
// the command that runs the render.
#include "mcxRenderCommand.h"

#include "mcxTransferFunctionSpec.h"

#include <cstdio>

namespace mcxapp
{

namespace
{
const char* const Usage = R"(usage: mcxray render [INPUT] [options]
       mcxray view [INPUT] [options]     (interactive; see mcxray view --help)

Renders a simulated X-ray image (a DRR): per pixel, the mean over the pixel's
area of the line integral of g = TF(density), reconstructed with the chosen
kernel, in TF units times world length (mm for medical data).

The world is DICOM patient space (LPS: x to the patient's left, y posterior,
z to the head) for every format: NIfTI (RAS), NRRD and MetaImage headers are
converted, so the same patient gives the same image from any file.

INPUT   a volume: .vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
        DICOM series directory (read with vtk-dicom: sorted by position, in
        patient space, rescaled to HU). Default: the bundled CT head (VTK's
        headsq).

options:
  --tf SPEC             transfer function: value:weight,value:weight,... in data
                        units (held constant beyond its end points), or a preset:
                        %s. Default: raw
  --samples N           number of samples, rounded up to 2^m - 1 (default 4194303;
                        at most 2^40 - 1, about 3 to 12 hours on 2 cores)
  --target-error E      choose the sample count for a relative RMS error E (a
                        pilot run of about 4 samples per pixel, at least 65535,
                        measures the image; up to 2^30 - 1 samples, with a
                        warning where those fall short of E); replaces
                        --samples. Without --deposit the deposit is chosen too:
                        a pilot of each measures its error and seconds, and the
                        one predicted to reach E soonest is taken, or every
                        voxel once when that is predicted sooner still (the
                        choice rests on measured times: give --deposit for the
                        same image bit for bit on every run)
  --quantization-levels L
                        choose the sample count by the paper's criterion: the
                        mean pixel deviation below one of L grey levels (the
                        deposit chosen as for --target-error)
  --method M            hybrid (default), mc, qmc (low-discrepancy kernel
                        offsets: with --deposit point; footprints need none, so
                        it is hybrid there), every-voxel (each voxel of
                        non-zero weight once, weighted by the TF: no sampling
                        noise while each voxel's footprint reaches at most 16
                        pixels, else a warning; replaces --samples; with
                        --stored-points, a cloud as large as those voxels), or
                        reference (exact, slow)
  --kernel K            tent (trilinear, default) or box (nearest neighbour)
  --deposit D           footprint (default: each sample adds its voxel's kernel
                        integrated over every pixel it reaches; about 4 to 50
                        times less error per sample) or point (the paper's: one
                        count where a random offset lands)
  --seed N              seed of the pseudo-random parts (default 0)
  --threads N           worker threads, at most the cores TBB may use (default: all
                        of them); results do not depend on it
  --memory-limit SIZE   memory budget (e.g. 8G; default: the machine's memory):
                        volumes, indices, images and clouds that need more are
                        refused before the stage that makes them, naming the size
  --series N            the N-th series of a DICOM folder that holds several (an
                        error lists them when N is missing)
  --read-timeout S      stop a reader that takes longer than S seconds (default
                        300; the volume is read in a child process, so a corrupt
                        file cannot crash or hang mcxray)
  --view AXIS           parallel view along +x, -x, +y, -y, +z or -z (default +z).
                        Image axis 0 runs along the first remaining world axis in
                        x, y, z order, axis 1 along the second; never mirrored.
                        x, y and z without a sign are +x, +y and +z.
  --camera P:F:U:KIND   any view: position P, focal point F and view-up U as
                        x,y,z triples, and KIND parallel=SCALE (half the image
                        height in world units) or angle=DEGREES (perspective,
                        vertical view angle), optionally followed by :near=D
                        (perspective: depth where integration starts; default
                        0.001 times the camera distance)
  --sad MM, --sid MM, --detector WxH, --pitch MM, --gantry DEG, --isocenter X,Y,Z
                        a cone-beam radiograph as radiographers give it (any one of
                        these selects it): source-to-axis distance (default 1000),
                        source-to-image distance (1500), detector pixels (512x512)
                        and pitch (0.8), gantry angle, isocentre (default: the
                        volume's centre). As in plastimatch drr: at angle a
                        the source is at isocentre + SAD (cos a, -sin a, 0),
                        on +x (the patient's left) at 0, anterior (-y) at 90;
                        image columns run along +y at angle 0, rows down -z.
                        Replaces --view, --camera, --size and --pixel-spacing
  --gantry START:STOP:COUNT
                        COUNT poses from START, STOP excluded (0:360:100 is
                        plastimatch's -a 100 -N 3.6), from one read and index:
                        a .vti or .mha output is one stack (slice k: pose k), a
                        .png or .pfm output NAME.EXT is NAME_0000.EXT, NAME_0001.EXT ...
  plastimatch's own options, the same meaning: -r/--dim "C R" (pixels,
                        columns first, as its images are), -z/--detector-size
                        "W H" (mm), -c/--image-center "C R" (pixel of the
                        isocentre's ray, from the top-left pixel), -o X Y Z,
                        -n/--nrm X Y Z (isocentre to source, instead of the
                        angle), --vup X Y Z (towards the top row; default 0 0 1),
                        -y/--gantry-angle DEG (degrees; plastimatch 1.9.4 reads
                        radians there), -a/--num-angles N and
                        -N/--gantry-angle-spacing DEG (a sweep from -y)
  --projection-matrix "P11 ... P34"
                        the view as a 3x4 matrix, row by row, with --detector:
                        world (LPS mm) to (u w, v w, w), u the column, v the row
                        from the top, 0 at the first pixel's centre (OpenCV's and
                        plastimatch's layout; any scale; affine, last row 0 0 0
                        1, for a parallel view)
  --projection-matrices FILE
                        a pose per matrix of FILE: the JSON --output-geometry
                        writes (each pose's P and size), or text of 12 numbers
                        per pose, row by row ('#' comments; --detector sizes)
  --intrinsics FX,FY,CX,CY --extrinsics R11,...,R33,T1,T2,T3
                        the same as OpenCV's K and [R | t] (world to camera: x
                        right, y down, z forward), with --detector
  --rtk-geometry FILE   every projection of RTK's circular geometry file
                        (RTKThreeDCircularGeometry, versions 2 and 3; flat
                        detector), with --detector, --pitch or -z, and
                        --detector-origin U,V (mm: the projections' origin as
                        RTK's tools take it; default centred): the images are
                        RTK's projections, row j of the .vti being RTK's row j;
                        pixels measured on the detector. Each <Matrix> must
                        agree with its parameters (as RTK checks)
  --rtplan FILE --beam N
                        the beam numbered N (else named N; the only beam
                        without --beam) of a DICOM RT Plan by IEC 61217, as a
                        planning system's DRR: gantry, collimator and couch
                        angles of its first control point about its
                        IsocenterPosition, its SourceAxisDistance (else --sad),
                        the detector at --sid, the image seen from the source
                        (gantry, collimator, couch 0: head up, the patient's
                        left on the right); head first supine patients only
  --output-geometry FILE
                        write each pose's P, K, R, t, source, size and spacing
                        as JSON (the .vti output holds P as field data
                        ProjectionMatrix, a tuple of 12 per pose)
  --coordinates C       lps (default) or ras (any case): the points, directions
                        and matrices of --camera, --isocenter, --nrm, --vup,
                        --projection-matrix and --extrinsics are in RAS (x to
                        the patient's right, y anterior) and are taken to LPS
                        by negating x and y; --view and --gantry name patient
                        directions either way
  --beer-lambert        output the intensity I0 exp(-line integral) (with --tf mu)
  --i0 I                unattenuated intensity I0 (default 1)
  --photons N           quantum noise: N photons reach an unattenuated pixel,
                        counts are Poisson (implies --beer-lambert; default off)
  --noise-seed N        seed of the noise (default 0; pose k of a sweep: N + k)
  --negative-log        output -ln(I / I0), the radiologist's display (bone bright)
  --spectrum S          a polychromatic radiograph (Documentation/polychromatic.md):
                        a tungsten tube "70kVp,2.5mmAl[,0.1mmCu][,12deg][,1keV]"
                        (filters: mm of an element) or a file of
                        "energy_keV photons" lines; the volume is in HU (no
                        --tf); samples drawn under the materials' density,
                        each deposit split into a channel per material
  --materials M         default (air, adipose, soft tissue, cortical bone;
                        add ",iodine=HU" and/or ",titanium=HU" thresholds) or
                        a materials file
  --detector-material M:MM[:G/CM3]
                        the detector's screen, e.g. CsI:0.6:4.51 (default: an
                        ideal absorber)
  --photon-counting     count photons (default: integrate energy)
  --size WxH            image size in pixels (default: 512 along the longer side)
  --pixel-spacing S     pixel size in world units on the detector plane
  --output FILE         .vti (float64 LineIntegral with geometry), .mha, .png or .pfm
                        (default: mcxray.png)
  --window LO:HI        PNG grey window in image units (default 0:maximum)
  --bits 8|16           PNG bit depth (default 8)
  --tolerance T         reference method: relative RMS tolerance (default 1e-3)
  --stored-points       store the point cloud (as an interactive view would),
                        then project it, and time the two stages apart; by
                        default samples are projected as they are generated
  --quiet               print nothing but errors
  --help                this text
)";
}

void PrintRenderUsage()
{
  std::printf(Usage, TransferFunctionPresetHelp());
}

} // namespace mcxapp
