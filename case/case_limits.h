#pragma once
// Every bound a case must keep, in one place so that docs and messages can quote them. They
// hold wherever a case is read (sph-server at Submit, sph-worker, sphctl): a case is text from
// anyone, and a program that reads it must not recurse, allocate or loop without bound.
// The shipped cases (cases/) stay far inside each of them.
#include <cstddef>

namespace sph {

// --- Shapes ---------------------------------------------------------------------------------
// How deep union, intersection, difference and shell may nest: a region's own shape is depth
// 1, a shape inside it depth 2, and so on. Compiling, bounding and walking a shape recurse over
// this tree.
inline constexpr int kMaxShapeDepth = 32;
// Shapes in a case, nested ones included. Every lattice point of a region evaluates each of its
// shapes, so this bounds the cost of estimating and building a case as well as its size.
inline constexpr int kMaxShapes = 1024;
// Polygon vertices in a case, all polygons together (a polygon's distance visits each vertex).
inline constexpr int kMaxPolygonVertices = 100000;
// Triangles of all meshes in a case (TriangleMesh, inlined from STL files): 500000 triangles
// inline to about 18 MB of case, and a distance query walks a hierarchy over them.
inline constexpr int kMaxMeshTriangles = 500000;
// Nodes of all signed-distance grids in a case (DistanceGrid, inlined from HDF5 files): a
// million values inline to about 30 MB of case text, below the service's 48 MiB.
inline constexpr int kMaxDistanceGridNodes = 1000000;

// --- Text -----------------------------------------------------------------------------------
// Message nesting the text-format parser follows: a shape at depth n sits 2n messages below
// the case (region, shape, then a kind and its shape per level) and needs two more for a box's
// corner, so a case that keeps kMaxShapeDepth always parses. Deeper text is refused by the
// parser before it recurses further.
inline constexpr int kMaxTextNesting = 2 * kMaxShapeDepth + 8;
// A case file read from disk (before point and reference data are inlined).
inline constexpr std::size_t kMaxCaseFileBytes = std::size_t{64} << 20;
// The canonical text (case_to_text) of a case that keeps these limits is at most this many
// times the text it was parsed from. It indents each line by its depth, so shapes nested to
// kMaxShapeDepth and written without spaces grow most; tests/unit/case_limits_test.cc measures
// the worst forms. (The one-line form grows far less.)
inline constexpr double kMaxCanonicalTextGrowth = 24;

// --- Strings --------------------------------------------------------------------------------
// Names (of the case, materials, regions, bodies, probes, open boundaries, result series) come
// back in listings, messages and file names.
inline constexpr std::size_t kMaxNameBytes = 256;
inline constexpr std::size_t kMaxDescriptionBytes = 16384;  // Case.description
inline constexpr std::size_t kMaxPathBytes = 4096;          // PointSet.file, series_data.file

// --- Counts of repeated parts -----------------------------------------------------------------
inline constexpr int kMaxMaterials = 256;
inline constexpr int kMaxRegions = 1024;  // fluids + walls + bodies
inline constexpr int kMaxPhaseTransitions = 256;
inline constexpr int kMaxProbes = 1024;
inline constexpr int kMaxOpenBoundaries = 254;   // their ids share a byte with "none"
inline constexpr int kMaxTableEntries = 100000;  // times of one time-function table or output

// --- Inlined data files -----------------------------------------------------------------------
// Explicit particle positions (PointSet), counted while a file is read so that a huge file is
// refused after kMaxPointsPerFile points, not read whole.
inline constexpr int kMaxPointsPerFile = 1000000;
inline constexpr int kMaxPointsPerCase = 2000000;
// Rows of a reference data file (reference.series_data.file), also counted while reading.
inline constexpr int kMaxReferenceRows = 100000;
// One line of a point or reference data file.
inline constexpr std::size_t kMaxDataLineBytes = 4096;

// --- Lengths and the lattice ------------------------------------------------------------------
// Lattice indices are int64 and positions doubles: every domain corner lies at most this many
// dx from lattice_origin along each axis (2^31), so index arithmetic cannot overflow and a
// lattice position keeps about 22 bits below dx.
inline constexpr double kMaxLatticeCellsPerAxis = 2147483648.0;
// Coordinates and lengths of the domain, lattice origin and shapes [m]: far beyond any
// laboratory or industrial scale, and their squares, cubes and inverses stay finite.
inline constexpr double kMaxCoordinate = 1e12;
// The smallest particle spacing [m]; h^-d of the kernels stays finite in 3D.
inline constexpr double kMinDx = 1e-12;

// --- Regions and the domain -------------------------------------------------------------------
// Each fluid, wall and body region must place at least one particle, and at least this
// fraction of the lattice points (or explicit points) of a fluid or a body must lie inside the
// domain. The scene builder drops whatever lies outside without a word, so a fluid or body
// mostly outside is a mistake in coordinates (a sign, a unit), not an intention; half leaves
// room for one that deliberately overhangs the domain. Points are counted in the domain and in
// a box as wide again on each side of every non-periodic axis: along a periodic axis the
// domain clips regions on purpose (a channel filled by a longer box). Walls need only place a
// particle: a slab or half-space clipped by the domain is a common way to write one, and what
// lies outside has no effect.
inline constexpr double kMinRegionFractionInDomain = 0.5;

// --- Work of validation and estimates ---------------------------------------------------------
// Validation and estimates test lattice points against the regions' shapes, and within the
// bounds above a region can span billions of points, a shape can hold a thousand parts or a
// hundred thousand polygon vertices, and a thousand regions can overlap: unbounded, a small
// request could cost minutes of CPU in the server thread that checks it. So each of these
// walks has a budget in units of Shape::cost() (one lattice point tested against a box is one
// unit); the regions share it by what they need (share_work in case/lattice.h), and a region
// that needs more than its share is counted on a sample of its lattice points. The shipped
// cases need a few percent of each budget, so they are counted exactly.
// Counting each region's points inside and around the domain (the checks above).
inline constexpr double kRegionCheckWork = 8e6;
// estimate_case: the particles of all regions, each tested against the regions that claim
// lattice points before it.
inline constexpr double kEstimateWork = 8e6;
// The wall-thickness check (case/wall_thickness.h) tags every lattice cell of the domain, so
// it cannot sample: a case that needs more is not checked.
inline constexpr double kWallCheckWork = 3e7;

// --- Errors -----------------------------------------------------------------------------------
// Errors validate_case reports; the rest are counted in one last error. Every vertex or point
// of a shape can be wrong on its own, and each error carries the field's path: without a cap a
// request of a few megabytes could make a reply of hundreds.
inline constexpr int kMaxReportedErrors = 100;

}  // namespace sph
