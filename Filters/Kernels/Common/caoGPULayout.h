/*
 * caoGPULayout.h - the one definition of ContextualAO's parameter blocks and
 * buffer layouts, compiled both as C++ (kernels, filters) and as GLSL
 * (compute shaders, via #include after vtk_encode_string embedding).
 *
 * Rules that keep the two sides identical:
 *  - every member is a 16-byte vec4/ivec4 (or a 32-byte dvec4, all of a
 *    block's first), so std140 and std430 agree with the C++ layout
 *    (checked by static_asserts at the end);
 *  - no bool, no vec3, no implicit padding;
 *  - constants are plain ints usable from both languages.
 */
#ifndef CAO_SHARED_H
#define CAO_SHARED_H

#ifdef __cplusplus
#include <cstdint>
namespace cao
{
namespace layout
{
struct vec4
{
  float x, y, z, w;
};
struct ivec4
{
  std::int32_t x, y, z, w;
};
struct dvec4
{
  double x, y, z, w;
};
using uint = std::uint32_t;
#define CAO_CONST static constexpr int
#else
#define CAO_CONST const int
#endif

/* Voxel categories written to the ClipCategory mask (paper: a, b, c). */
CAO_CONST CAO_CATEGORY_CLIPPED = 0;    /* a: fully clipped, not recomputed */
CAO_CONST CAO_CATEGORY_AFFECTED = 1;   /* b: LAO recomputed on the clipped opacity */
CAO_CONST CAO_CATEGORY_UNAFFECTED = 2; /* c: precomputed LAO copied */

/* Clip modes (paper: subtraction and probing). */
CAO_CONST CAO_MODE_SUBTRACT = 0; /* remove what is inside the mesh */
CAO_CONST CAO_MODE_PROBE = 1;    /* keep only what is inside the mesh */

/* Anti-aliased clipping: centre + 8 corners, then up to this many extra
 * samples where those 9 disagree. */
CAO_CONST CAO_MAX_AA_EXTRA_SAMPLES = 32;

/*
 * One tap of the LAO ray march: the position of sample m of ray k relative
 * to the voxel, in index space, split into the lower corner of the
 * trilinear cell (integer) and the position inside that cell (fraction).
 * The fraction is the same for every voxel, which is what makes the march
 * a fixed 8-tap stencil per sample.
 */
struct LAOTap
{
  ivec4 cell; /* xyz: lower-corner offset in voxels; w: linear offset of that corner */
  vec4 frac;  /* xyz: trilinear fractions in [0,1); w: unused (0) */
};

struct LAOMarchBlock
{
  ivec4 dims;        /* xyz: voxels per axis; w: parity of the global origin (bit d: axis d) */
  ivec4 strides;     /* xyz: linear strides (1, nx, nx*ny); w: 0 */
  ivec4 rays;        /* x: rays K; y: samples per ray M; z: taps per ray (M-1);
                        w: variants V (1, or 8 interleaved over 2x2x2 voxels) */
  ivec4 interiorMin; /* xyz: first voxel index whose every tap is in bounds */
  ivec4 interiorMax; /* xyz: last voxel index whose every tap is in bounds */
  vec4 norm;         /* x: float(K*M), the divisor of the summed transmittances */
};

/*
 * Per-pose clipping parameters. toCamera maps a continuous voxel index
 * (x, y, z, 1) to the clipping camera's (u, v, depth): u and v in depth-map
 * pixels, depth in the mesh's local length unit along the view direction.
 * Each row is evaluated as ((r.x*x + r.y*y) + r.z*z) + r.w, in that order.
 */
struct ClipParams
{
  vec4 toCamera[3];
  ivec4 map;    /* x: width; y: height; z: layers; w: mode (CAO_MODE_*) */
  ivec4 aa;     /* x: extra AA samples N; yzw: 0 */
  ivec4 boxMin; /* xyz: first voxel of the candidate box (inclusive) */
  ivec4 boxMax; /* xyz: last voxel of the candidate box (inclusive) */
  vec4 aaOffsets[CAO_MAX_AA_EXTRA_SAMPLES]; /* xyz in [-0.5,0.5]: extra AA positions */
};

/*
 * One frame of the ray caster (caoRayCaster, caoRayCastFS.glsl). Matrices
 * are column-major, as GLSL's mat4(c0, c1, c2, c3): ndcToWorld takes a
 * window's normalised device coordinates to world space, worldToIndex takes
 * world space to the volume's 0-based voxel index (x, y, z), and
 * normalToWorld (3 columns) takes an index-space gradient to a world-space
 * normal (the inverse transpose of index-to-world's linear part). "World"
 * here is the scene's world translated so that the volume's centre is its
 * origin: a volume far from the origin keeps its placement in float, and
 * distances and directions are the world's.
 */
#define CAO_MAX_LIGHTS 8 /* lights the ray caster shades with (the renderer's first 8 switched on) */
/* The half-space table the calibration reads (cao::HalfSpaceTable): integer depths below an open
 * face, 0 (the last empty layer) to LAYERS - 1, times LAO-step opacities 0, 1/16, ..., 1. */
#define CAO_HALF_SPACE_LAYERS 16
#define CAO_HALF_SPACE_OPACITIES 17
#define CAO_HALF_SPACE_VEC4S 68 /* 16 * 17 floats, four to a vec4 */
struct RenderParams
{
  vec4 ndcToWorld[4];
  vec4 worldToIndex[4];
  vec4 normalToWorld[3];
  vec4 viewport;  /* x, y: first pixel; z, w: 1 / width, 1 / height */
  vec4 lights[CAO_MAX_LIGHTS];      /* xyz: world direction towards light l; w: 1 = headlight
                                      (along the view ray) */
  vec4 lightColors[CAO_MAX_LIGHTS]; /* rgb: light l's colour times its intensity; w: 0 */
  vec4 shading;   /* x: ambient, y: diffuse, z: specular, w: specular power */
  vec4 sampling;  /* x: step (world units); y, z: table coordinate = texel * y + z; w: AO strength */
  vec4 invDims;   /* xyz: 1 / voxels per axis (texture coordinate = (index + 0.5) * invDims); w: 0 */
  ivec4 dims;     /* xyz: voxels per axis; w: CAO_RENDER_* flags */
  ivec4 limits;   /* x: maximum samples per ray; y: lights (0 to CAO_MAX_LIGHTS); z: the depth-peeling
                     stage (CAO_PEEL_*; with CAO_RENDER_PEEL); w: the image sample distance k (0 or
                     1: every pixel; k > 1: one ray per k x k pixels into the caster's own target,
                     which caoUpsampleFS.glsl spreads over the viewport) */
  vec4 boxMax;    /* xyz: the last voxel index (the box is [0, boxMax]); w: early termination alpha */
  vec4 aoCalibration; /* CAO_RENDER_AO_CALIBRATED: x: the LAO of a voxel enclosed by opaque matter
                         (halfSpace's deepest layer at opacity 1); y, z: 0; w: LAO step / ray-cast
                         step (table opacity -> LAO opacity) */
  vec4 halfSpace[CAO_HALF_SPACE_VEC4S]; /* CAO_RENDER_AO_CALIBRATED: cao::HalfSpaceTable, element
                         depth * CAO_HALF_SPACE_OPACITIES + opacity step */
};
CAO_CONST CAO_RENDER_SHADE = 1;        /* gradient Blinn-Phong */
CAO_CONST CAO_RENDER_AO = 2;           /* the AO volume scales the ambient term */
CAO_CONST CAO_RENDER_CLIP = 4;         /* shadow-test clipping against the depth maps */
CAO_CONST CAO_RENDER_JITTER = 8;       /* per-pixel ray-start offset */
CAO_CONST CAO_RENDER_OPAQUE_DEPTH = 16; /* stop at the opaque geometry's depth */
CAO_CONST CAO_RENDER_AO_CALIBRATED = 32; /* the AO as the light an open face would get (aoCalibration) */
CAO_CONST CAO_RENDER_CLIP_SMOOTH = 64; /* the picture's clip test blends the 4 nearest map pixels */
CAO_CONST CAO_RENDER_CLIP_ENTRY = 128; /* the first sample behind a cut moves onto the clip surface */
CAO_CONST CAO_RENDER_PEEL = 256; /* drawn inside a host's dual depth peeling (limits.z: the stage) */
CAO_CONST CAO_RENDER_OWN_TARGET = 512; /* drawn into the caster's own target, spread afterwards (as k > 1) */
/* The stages of VTK's dual depth peeling a volume is drawn in (vtkDualDepthPeelingPass): the
 * ray segments outside the translucent geometry's depth range (front and back outputs), one
 * peel between two translucent layers, and the alpha-blended remainder. */
CAO_CONST CAO_PEEL_OUTSIDE = 1;
CAO_CONST CAO_PEEL_LAYER = 2;
CAO_CONST CAO_PEEL_REMAINDER = 3;

/*
 * Binding points, shared so that the C++ side binds what the GLSL declares.
 * Plain #defines: GLSL 4.30 layout qualifiers need literal-like constants.
 */
#define CAO_BINDING_LAO_MARCH 0    /* uniform block: LAOMarchBlock */
#define CAO_BINDING_CLIP_PARAMS 1   /* uniform block: ClipParams */
#define CAO_BINDING_TAPS 0          /* storage: LAOTap[K*(M-1)] */
#define CAO_BINDING_OPACITY_TABLE 1 /* storage: float opacity per scalar value */
#define CAO_BINDING_CLIP_FACTORS 2  /* storage: float clip factor per coverage count */
#define CAO_BINDING_MAPS 3          /* storage: front, back, candidate front, candidate back */
#define CAO_BINDING_COUNTERS 4      /* storage: uint category counts (a, b, c) */
#define CAO_BINDING_RENDER_PARAMS 2 /* uniform block: RenderParams */
#define CAO_UNIT_SCALARS 0          /* sampler3D: scalars (normalised integer view or float) */
#define CAO_UNIT_AO 1               /* sampler3D: AO (16-bit normalised view) */
#define CAO_UNIT_TABLE 2            /* sampler2D: RGBA transfer-function table, 1 row */
#define CAO_UNIT_DEPTH 3            /* sampler2D: the opaque geometry's depth */
#define CAO_UNIT_STATE 4            /* usampler3D: the clip state (category << 6 | count) */
/* CAO_RENDER_PEEL: the host's peeling textures, bound by the ray caster on units of its own. */
#define CAO_UNIT_PEEL_OUTER 5       /* sampler2D RG: (-near, far) outer depths (the remainder's range) */
#define CAO_UNIT_PEEL_INNER 6       /* sampler2D RG: (-near, far) inner depths */
#define CAO_UNIT_PEEL_FRONT 7       /* sampler2D RGBA: the front colour accumulated so far */
#define CAO_UNIT_PEEL_OPAQUE 8      /* sampler2D: the opaque geometry's depth */
/* caoUpsampleFS.glsl (another program): the ray cast drawn at one pixel in k x k */
#define CAO_UNIT_LOW_BACK 9         /* sampler2D RGBA16F: its back (or only) output */
#define CAO_UNIT_LOW_FRONT 10       /* sampler2D RGBA16F: its front output (depth peeling) */
/* The AO samples (caoAOSamples.glsl, the ray caster's own volume): per voxel, keep = 0 where the
 * clip removed it (with CAO_RENDER_CLIP), else 1: (keep * AO, keep, keep * the LAO step's opacity,
 * keep * (opacity > 0)), with the LAO's own opacity (the AO engine's), RGBA16; linear filtering gives VoxelAO's trilinear sums in one fetch. */
#define CAO_UNIT_AO_SAMPLES 11      /* sampler3D RGBA16: the AO samples */
#define CAO_UNIT_HALF_SPACE 12      /* sampler2D R32F: RenderParams::halfSpace, CAO_HALF_SPACE_OPACITIES
                                       wide, CAO_HALF_SPACE_LAYERS high, filtered (one fetch per lookup) */
#define CAO_IMAGE_AO_SAMPLES 1      /* image unit rgba16: the AO samples, written (the engine's
                                       volume read at CAO_IMAGE_VOLUME) */
/* The depth-map programs (caoClipDepthMapsGL) are separate programs with their
 * own storage bindings, kept within the 8 that GL 4.3 guarantees. */
#define CAO_BINDING_DM_POINTS 0    /* storage: double xyz per mesh point (local frame) */
#define CAO_BINDING_DM_IDS 1       /* storage: int, 3 point ids per triangle */
#define CAO_BINDING_DM_TRIANGLES 2 /* storage: DMTriangle per triangle */
#define CAO_BINDING_DM_HEADS 3     /* storage: uint per pixel, first hit of its list */
#define CAO_BINDING_DM_HITS 4      /* storage: DMHit per covered (pixel, triangle) */
#define CAO_BINDING_DM_MAPS 5      /* storage: six maps (see caoClipDepthMapsGL.h) */
#define CAO_BINDING_DM_WINDOW 6    /* storage: DMOffset per dilation window pixel */
#define CAO_BINDING_DM_STATS 7     /* storage: int counters (CAO_DM_STAT_*), layer boxes */
#define CAO_IMAGE_VOLUME 0          /* scalars (r8ui/r16ui) or opacity (r32f) */
#define CAO_IMAGE_STATE 1           /* r8ui: category << 6 | coverage count */
#define CAO_IMAGE_AO_IN 2           /* r16ui: precomputed AO */
#define CAO_IMAGE_AO_OUT 3          /* r16ui: current AO */

/*
 * The per-voxel clip state the GPU keeps (one byte): the category in the
 * top two bits and the anti-aliasing coverage count (0 .. 9 + N) in the low
 * six. The clipped opacity is opacity * clipFactor[count], with the factor
 * table computed on the CPU exactly as caoClassify computes 1 - c or c.
 */
CAO_CONST CAO_STATE_CATEGORY_SHIFT = 6;
CAO_CONST CAO_STATE_COUNT_MASK = 63;
/* AO is stored on the GPU as 16-bit unsigned normalised: q = uint(ao * 65535 + 0.5). */
CAO_CONST CAO_AO_SCALE = 65535;

/*
 * Depth maps on the GPU. caoClipDepthMaps.cxx works in double; so do these
 * records and the shaders that use them, operation for operation, so that
 * the GPU maps are the CPU maps bit for bit. Doubles are 8-byte aligned in
 * both std430 and C++; each struct is padded to a multiple of 16 by hand.
 */
struct DMTriangle
{
  double u[4]; /* pixel coordinates of the corners (counter-clockwise); [3] unused */
  double v[4];
  double z[4]; /* depths of the corners */
  ivec4 ids;   /* xyz: the corners' point ids (canonical edge order); w: winding (+1/-1) */
  ivec4 box;   /* pixels [x, z] x [y, w] whose centres may be covered; empty if x > z */
};
struct DMHit
{
  double z;          /* depth of the crossing */
  int winding;       /* +1 entering, -1 leaving */
  uint next;         /* next hit of the same pixel, CAO_DM_END at the end */
};
struct DMOffset
{
  int dx, dy; /* window offset in pixels */
  double h;   /* sqrt(radius^2 - gap^2): the depth slack at that offset */
};
CAO_CONST CAO_DM_STAT_COVERED = 0;   /* pixels with an interval */
CAO_CONST CAO_DM_STAT_OVERFLOW = 1;  /* pixels with more intervals than layers */
CAO_CONST CAO_DM_STAT_UNMATCHED = 2; /* pixels whose winding did not return to 0 */
CAO_CONST CAO_DM_STAT_NONFINITE = 3; /* triangles with a non-finite projection */
CAO_CONST CAO_DM_STAT_HITS = 4;      /* hits appended (the allocation counter) */
CAO_CONST CAO_DM_STAT_BOXES = 8;     /* then per layer: covered x0, y0, x1, y1 */
#define CAO_DM_END 0xFFFFFFFFu

/*
 * Voxel cone tracing (Dalla Favera and Celes; caoVoxelConeTracing.h is the CPU twin,
 * caoVCTGL the GPU side). The grid: column (i, j) holds `words` 32-bit
 * words, slice k in bit k % 32 of word k / 32, column-major as the CPU's
 * BitGrid. The voxelizer (caoVoxelize.glsl) reads the points in grid units
 * ((p - origin) / h, double, computed by the host as the CPU does) and 3
 * ids per triangle; one workgroup per triangle walks its column box.
 */
#define CAO_VCT_MAX_CONES 8
#define CAO_VCT_MAX_SPHERES 16
#define CAO_VCT_MAX_PRISMS 32
#define CAO_VCT_MAX_VOLUMES 8
/* A volume occluding the surfaces (cao::OpacityVolume): its opacity per
 * voxel in the buffer CAO_BINDING_VCT_OPACITY from `dims.w` on, x fastest;
 * `toIndex` maps the grid's frame (world units, the frame the points come
 * in) to its continuous voxel index (voxel centres at integers), composed
 * on the host in double from the grid's axes and the volume's world to
 * index matrix. */
struct VCTVolume
{
  vec4 toIndex[3]; /* rows of a 3 x 4 matrix */
  ivec4 dims;      /* xyz: voxels per axis; w: the first value's index in the opacity buffer */
  vec4 scalars;    /* x: 1 / the opacity's unit distance (world); yzw: 0 */
};
struct VCTParams
{
  ivec4 grid;   /* x: nx, y: ny, z: slices, w: words per column */
  vec4 origin;  /* xyz: the grid's corner (world); w: 1 / voxel size */
  ivec4 counts; /* x: cones, y: spheres, z: prisms, w: points */
  vec4 apex;    /* x: apex offset along the normal (world units); y: occupancy (1 rays, 0 volume);
                   z: ray step (world units); w: tan(cone half-angle) */
  vec4 cones[CAO_VCT_MAX_CONES];     /* xyz: direction, z along the normal; w: weight */
  vec4 spheres[CAO_VCT_MAX_SPHERES]; /* x: centre distance t, y: radius r (world); zw: 0 */
  vec4 disk[CAO_VCT_MAX_PRISMS];     /* xy: unit-disk sample, z: sqrt(1 - x^2 - y^2); w: 0 */
  vec4 frustum[5];                   /* the frustum grid (BitGrid::Frustum): rows 0-3 the grid frame to
                                        clip; [4] x: 1 a frustum grid (else 0), y: 1 perspective, z: world
                                        length per unit of depth, w: 0; its columns' near depth and slices
                                        per depth in CAO_BINDING_VCT_COLUMNS */
  ivec4 volumeCount;                 /* x: occluding volumes (0..CAO_VCT_MAX_VOLUMES); y: the points are
                                        pixels of rows this long, turned by `rotations` (0: not turned);
                                        zw: 0 */
  vec4 rotations[4];                 /* the 4 x 4 pattern's turns about the normal (radians), pixel cell
                                        i % 4 + 4 (j % 4) at [cell / 4][cell % 4] (VCTPatternRotations) */
  VCTVolume volumes[CAO_VCT_MAX_VOLUMES];
};
#define CAO_BINDING_VCT_PARAMS 3   /* uniform block: VCTParams */
#define CAO_BINDING_VX_POINTS 0    /* storage: double xyz per point, grid units */
#define CAO_BINDING_VX_IDS 1       /* storage: int, 3 point ids per triangle */
#define CAO_BINDING_VX_BITS 2      /* storage: uint, the mesh's own bits (voxelize) / the grid (trace) */
#define CAO_BINDING_VX_GRID 3      /* storage: uint, the grid the mesh is OR'ed into */
#define CAO_BINDING_VX_SURFACE 7   /* storage: uint, a closed mesh's surface voxels (OR'ed with its parity) */
#define CAO_BINDING_VX_COLUMNS 4   /* storage: double per column, near depth and slices per depth (frustum) */
#define CAO_BINDING_VX_PARITY 5    /* storage: uint per column, its crossings' parity (frustum, solid) */
#define CAO_BINDING_VCT_COLUMNS 0  /* storage: vec2 per column, near depth and slices per depth (frustum) */
#define CAO_BINDING_VCT_POINTS 4   /* storage: vec4 per point (xyz world; w: with a row length (VCTParams
                                      volumeCount.y), w > 1e30 where no pixel is covered, as the filter reads) */
#define CAO_BINDING_VCT_NORMALS 5  /* storage: vec4 per point (xyz unit normal; w 0: no point, AO NaN) */
#define CAO_BINDING_VCT_AO 6       /* storage: float AO per point */
#define CAO_BINDING_VCT_OPACITY 7  /* storage: float, the occluding volumes' opacity (VCTVolume; the
                                      trace's, where the voxelizer binds VX_SURFACE: within the 8
                                      bindings OpenGL 4.3 guarantees and the state guard restores) */

/* A frame kept on the GPU (caoFrameGL, caoFrame.glsl; the pass's GPU path
 * with the depth G-buffer): the drawn depth read into a buffer, the colours
 * blitted into textures,
 * the G-buffer (cao::FrameFromDepth's twin, in double) written where the
 * cone tracer reads its points and normals, the AO combined into the
 * colours there. */
struct FrameParams
{
  vec4 ndcToWorld[4]; /* rows (double on the host, float here: the shader gets them in double too, below) */
  vec4 ndcToWorldLow[4]; /* rows: the double's remainder (ndcToWorld + low = the double) */
  vec4 toGrid[3];     /* rows of the grid's axes (BitGrid::ToGrid), w 0 */
  ivec4 image;        /* x: width, y: height, z: 1 whole colour, 0 ambient term; w: 0 */
  vec4 scalars;       /* x: strength; yzw: 0 */
};
#define CAO_BINDING_FR_PARAMS 1    /* uniform block: FrameParams */
#define CAO_BINDING_FR_DEPTH 0     /* storage: float per pixel, the drawn depth (0..1; 1: background),
                                      where it cannot be blitted (else a texture on CAO_UNIT_DEPTH) */
#define CAO_BINDING_FR_PREVIOUS 1  /* storage: float per pixel, the last traced frame's depth (else a
                                      texture on CAO_UNIT_STATE) */
#define CAO_IMAGE_FR_COLOR 0       /* image unit: rgba32f, the drawn colour (blitted in), combined in place */
#define CAO_IMAGE_FR_AMBIENT 1     /* image unit: rgba32f, the ambient term's drawing (blitted in) */
#define CAO_BINDING_FR_COUNT 7     /* storage: uint [2]: pixels whose depth changed, covered pixels */
/* The G-buffer goes to CAO_BINDING_VCT_POINTS / _NORMALS (normal w: 1 covered, 0 not), the AO
 * is read from CAO_BINDING_VCT_AO (NaN: not covered). */

/* The screen-space surface AO (caoScreenSpaceAO.h, caoScreenAO.glsl): one
 * block for horizon-based AO and volumetric AO; the frame's pixels as vec4
 * buffers; Volumetric AO's disk samples (16 sets of up to 256) as a buffer. */
#define CAO_SS_TILE 4
#define CAO_SS_MAX_SAMPLES 4096 /* 16 sets x VolumetricAOSettings' 256 samples */
#define CAO_SS_MAX_FILTER_WEIGHTS 20 /* 2 x HBAOSettings' 8 taps + 1, in whole vec4s */
struct ScreenAOParams
{
  vec4 worldToNDC[4]; /* rows */
  vec4 ndcToWorld[4]; /* rows */
  ivec4 image;        /* x: width, y: height, z: method (0 hbao, 1 volumetric), w: pattern tile side (4 or 1) */
  ivec4 hbao;         /* x: directions, y: steps, z: normal rays, w: flags (1 deflect, 2 linear attenuation) */
  ivec4 volumetric;          /* x: samples per pixel, y: sets, z: halo guard, w: 0 */
  vec4 scalars;       /* x: radius R (world), y: offset (pixels), zw: 0 */
  vec4 pattern[CAO_SS_TILE * CAO_SS_TILE]; /* hbao per tile cell: x rotation (radians), y jitter (0, 1] */
  vec4 finish;        /* the blur or filter (caoScreenFilter.glsl, cao::DepthAwareFilter): x taps each side
                         (0: none), y tolerance (world), z 1: clamp to [0, 1] after (Volumetric AO); w: the taps'
                         reach from the pixel's point (world; 0: unlimited) */
  vec4 finishWeights[CAO_SS_MAX_FILTER_WEIGHTS / 4]; /* the taps' weights per axis, -r..r, 4 a row */
};
/* Within the bindings OpenGL 4.3 guarantees (8 storage, uniform 0-3) and
 * that caoGLStateGuard restores in a host's context. */
#define CAO_BINDING_SS_PARAMS 2    /* uniform block: ScreenAOParams */
#define CAO_BINDING_SS_POSITIONS 0 /* storage: vec4 per pixel (xyz world, w NDC depth; w > 1e30: none) */
#define CAO_BINDING_SS_NORMALS 1   /* storage: vec4 per pixel (xyz unit normal facing the camera, w its world size) */
#define CAO_BINDING_SS_AO 2        /* storage: float per pixel (NaN: not covered) */
#define CAO_BINDING_SS_DISK 3      /* storage: vec4 per sample (xy on the disk, world units; zw 0) */
#define CAO_BINDING_SS_FILTERED 4  /* storage: float per pixel, the blurred or filtered AO (NaN: not
                                      covered; the frame's AO buffer on the GPU frame) */

/* Line AO (Kernels/Lines/caoLineAO.h, GL/Lines/shaders/caoLineAO.glsl): the
 * rays (flag 4) or the prisms of each covered pixel's half ball, through the
 * lines' bit grid (and the solids', planned alike). The host sets each half ball up in
 * double (cao::LineHalfBallOfPixel) and packs it as a LineAOPixel. */
struct LineAOParams
{
  ivec4 grid;    /* x: nx, y: ny, z: slices, w: 32-bit words per column */
  ivec4 counts;  /* x: samples per set, y: half balls (pixels), z: flags (1 paper weights, 2 solids, 4 rays), w: 0 */
  vec4 scalars;  /* x: R (voxels), y: voxel (world), z: occlusion scale s (cao::LineOcclusionScale), w: strength */
  vec4 paper;    /* x: the paper's AO factor; y: the rays' extinction per voxel, strength x cao::LineVoxelExtinction;
                    z: where along a ray a line voxel starts to dim it (voxels, LineAOSettings::voxelOffset); w: 0 */
};
struct LineAOPixel
{
  vec4 centre;   /* xyz: the half ball's centre (voxel units); w: its base plane's offset along plane.xyz */
  vec4 plane;    /* xyz: the base plane's unit normal (grid frame); w: 0 */
  vec4 tangent;  /* xyz: the line's unit tangent (grid frame; 0: a point); w: 0 */
  ivec4 pixel;   /* x: the output index, y: flags (1 a line, 2 cosine weight, 4 none: the AO is NaN), z: sample set, w: 0 */
};
#define CAO_LA_MAX_SETS 16

/* Line voxelization (cao::VoxelizeLines on the GPU, caoLineVoxelize.glsl):
 * one invocation per segment, its pieces' boxes visited as the CPU does,
 * the bits OR-ed atomically. The host maps the segments' ends to voxel
 * units in double (the grid frame, origin at 0) and packs them as two
 * vec4 per segment. */
struct LineVoxelizeParams
{
  ivec4 grid;    /* x: nx, y: ny, z: slices, w: 32-bit words per column */
  ivec4 counts;  /* x: segments; yzw: 0 */
  vec4 tube;     /* x: the tube radius (voxels), y: its square, z: the piece length (voxels), w: 0 */
};
#define CAO_BINDING_LV_PARAMS 2   /* uniform block: LineVoxelizeParams */
#define CAO_BINDING_LV_MAP 3      /* uniform block: LineGridMap (CAO_LV_WORLD: the ends are the G-buffer's
                                     world segments, LG_SEGMENTS, mapped here) */
#define CAO_BINDING_LV_ENDS 1     /* storage: vec4 per segment end (xyz voxel units), two per segment */
#define CAO_BINDING_LV_BITS 0     /* storage: uint, the lines' grid (the same buffer LA_BITS reads) */
/* The line G-buffer on the GPU (caoLineGBuffer.glsl, the twin of
 * cao::LineFrameFromDepth with drawings, in double): each drawn pixel's
 * ray, each segment's candidate pixels (a key per pixel: covering first,
 * then the frontmost, else the nearest; the lowest segment of that key),
 * and each chosen pixel's half ball as a LineAOPixel (the prisms' input),
 * in one pass per stage. Slots are the drawn pixels, numbered by the host. */
/* A world point to the lines' grid's voxel units (cao::BitGrid::ToGrid,
 * less the origin, over the voxel), in double: caoLineGridMap.glsl. */
struct LineGridMap
{
  dvec4 rows[3]; /* rows of the grid's axes (world -> grid frame); w: the grid's origin on that row */
  dvec4 voxel;   /* x: the voxel's side (world); yzw: 0 */
};
struct LineGBufferParams
{
  dvec4 ndcToWorld[4];  /* rows of the camera's NDC -> world matrix */
  dvec4 worldToClip[4]; /* rows of its inverse */
  LineGridMap map;      /* the grid the half balls are in */
  dvec4 scalars;        /* x: the screen scale (pixels on screen per pixel of reach), y: the widest depth
                           slack (window depth), z: the tube radius (voxels), w: the widest reach (pixels) */
  dvec4 constants;      /* x: MaximumDepthSlack, y: LineCoverSlack, z: half a voxel's diagonal, w: 0 */
  ivec4 counts;         /* x: width, y: height, z: segments, w: drawn pixels (slots) */
  ivec4 flags;          /* x: 1 the half ball at the tube's surface (LineAOHemisphere::Normal); yzw: 0 */
};
struct LineRay
{
  dvec4 origin;    /* xyz: the near-plane point; w: the drawn point's distance along the ray */
  dvec4 direction; /* xyz: unit; w: the pixel's footprint at the drawn depth (-1: no ray, no candidate) */
  dvec4 drawn;     /* xyz: the drawn point; w: how far behind it a line may lie */
};
#define CAO_BINDING_LG_PARAMS 2   /* uniform block: LineGBufferParams */
#define CAO_BINDING_LG_SLOTS 0    /* storage: int per pixel, its slot (-1: not drawn, or another kind's) */
#define CAO_BINDING_LG_DRAWN 1    /* storage: uvec2 per slot (x: pixel, y: window depth's float bits) */
#define CAO_BINDING_LG_RAYS 2     /* storage: LineRay per slot */
#define CAO_BINDING_LG_SEGMENTS 3 /* storage: dvec4 pair per segment (xyz ends; first w: its drawing) */
#define CAO_BINDING_LG_DRAWINGS 4 /* storage: dvec4 per drawing (reach, half width (pixels), depth slack,
                                     1 tubes) */
#define CAO_BINDING_LG_KEYS 5     /* storage: uvec2 per slot (x: the best key, y: its lowest segment) */
#define CAO_BINDING_LG_RECORDS 6  /* storage: LineAOPixel per slot (pixel.y flag 4: no line) */
#define CAO_BINDING_LA_PARAMS 2   /* uniform block: LineAOParams */
#define CAO_BINDING_LA_BITS 0     /* storage: uint, the lines' grid ((j nx + i) words + word) */
#define CAO_BINDING_LA_SOLIDS 1   /* storage: uint, the solids' grid (flag 2), planned as the lines' */
#define CAO_BINDING_LA_PIXELS 2   /* storage: LineAOPixel per half ball */
#define CAO_BINDING_LA_SAMPLES 3  /* storage: vec4 per disk sample (xy; zw 0), set s from s x samples */
#define CAO_BINDING_LA_AO 4       /* storage: float AO per half ball */

#ifdef __cplusplus
static_assert(sizeof(ScreenAOParams) == (13 + CAO_SS_MAX_FILTER_WEIGHTS / 4 + CAO_SS_TILE * CAO_SS_TILE) * 16,
  "ScreenAOParams must match std140");
static_assert(sizeof(FrameParams) == 13 * 16, "FrameParams must match std140");
static_assert(sizeof(LineAOParams) == 4 * 16, "LineAOParams must match std140");
static_assert(sizeof(LineAOPixel) == 4 * 16, "LineAOPixel must match std430");
static_assert(sizeof(LineVoxelizeParams) == 3 * 16, "LineVoxelizeParams must match std140");
static_assert(sizeof(LineGridMap) == 4 * 32, "LineGridMap must match std140");
static_assert(sizeof(LineGBufferParams) == 14 * 32 + 2 * 16, "LineGBufferParams must match std140");
static_assert(sizeof(LineRay) == 3 * 32, "LineRay must match std430");
static_assert(sizeof(DMTriangle) == 128, "DMTriangle must match std430");
static_assert(sizeof(DMHit) == 16, "DMHit must match std430");
static_assert(sizeof(DMOffset) == 16, "DMOffset must match std430");
static_assert(sizeof(RenderParams) == (19 + 2 * CAO_MAX_LIGHTS + CAO_HALF_SPACE_VEC4S) * 16,
  "RenderParams must match std140");
static_assert(sizeof(LAOTap) == 32, "LAOTap must match std430");
static_assert(sizeof(VCTVolume) == 5 * 16, "VCTVolume must match std140");
static_assert(sizeof(VCTParams) ==
    9 * 16 + (CAO_VCT_MAX_CONES + CAO_VCT_MAX_SPHERES + CAO_VCT_MAX_PRISMS + 5) * 16 +
      CAO_VCT_MAX_VOLUMES * sizeof(VCTVolume),
  "VCTParams must match std140");
static_assert(sizeof(LAOMarchBlock) == 96, "LAOMarchBlock must match std140/std430");
static_assert(sizeof(ClipParams) == 3 * 16 + 4 * 16 + CAO_MAX_AA_EXTRA_SAMPLES * 16,
  "ClipParams must match std140/std430");
} // namespace layout
} // namespace cao
#endif

#undef CAO_CONST
#endif
