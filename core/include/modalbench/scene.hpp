#pragma once
// A scene: one beam or plate, its material, supports, loads and what is asked of it.
//
// A Scene is a method-agnostic value in SI units. It says nothing about how a back-end
// discretizes it (that is the back-end's `Discretization`). Scenes are read from TOML
// (see README.md, "Scene format") and validated on load: every rule that fails names the
// file, the key and the reason (`InputError`).
//
// Coordinates: x along the beam axis / plate length a, y across (plate width b), z up.
// Deflection w is along +z; rotations are right-handed about the axes, so for a beam
// bending in x-z the section rotation theta_y equals -dw/dx (Euler-Bernoulli).

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace modalbench {

/// Invalid input: carries the source (file), the key and the reason.
class InputError : public std::runtime_error {
 public:
  InputError(std::string source, std::string key, std::string reason);
  const std::string& source() const { return source_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string source_, key_, reason_;
};

enum class SceneKind { Beam, Plate, Frame };
/// Which fields a beam carries. Plates are always `Bending` (w, theta_x, theta_y).
enum class Physics {
  Bending,  ///< transverse bending in x-z only
  Planar,   ///< axial + bending in x-z
  Spatial,  ///< axial, bending in x-z and x-y, torsion (6 DOF)
  Lateral,  ///< a rotor's lateral model: bending in x-z and x-y (v, w, theta_y, theta_z), no axial, no torsion
};
/// Which fields a beam of this physics carries besides w and theta_y.
inline bool carries_axial(Physics p) { return p == Physics::Planar || p == Physics::Spatial; }
inline bool carries_xy(Physics p) { return p == Physics::Spatial || p == Physics::Lateral; }
inline bool carries_torsion(Physics p) { return p == Physics::Spatial; }
/// The continuum theory the `exact` reference solves (back-ends state their own model).
enum class Theory { EulerBernoulli, Timoshenko, Kirchhoff, Mindlin };

std::string to_string(SceneKind);
std::string to_string(Physics);
std::string to_string(Theory);

inline constexpr double kRigid = std::numeric_limits<double>::infinity();

/// Support of one beam end or plate edge: a spring per DOF, each in [0, +inf] (inf = rigid).
/// Beam end: N/m, N*m/rad. Plate edge: per unit length of edge, N/m^2 and N*m/(rad*m).
struct Support {
  std::string kind = "free";  ///< free | pinned | clamped | guided | springs
  double translational = 0.0; ///< transverse (w; for spatial beams also v)
  double rotational = 0.0;    ///< bending rotation (theta_y; spatial also theta_z); plate: about the edge
  double axial = 0.0;         ///< beam only: u along x
  double torsional = 0.0;     ///< beam only: theta_x

  static Support named(const std::string& kind);  ///< throws std::invalid_argument if unknown
  bool is_free() const { return translational == 0 && rotational == 0 && axial == 0 && torsional == 0; }
};

struct Material {
  double E = 0;      ///< Young's modulus, Pa
  double G = 0;      ///< shear modulus, Pa (given, or E / (2 (1 + nu)))
  double nu = 0;     ///< Poisson's ratio (given, or E / (2 G) - 1)
  double rho = 0;    ///< density, kg/m^3
  double kappa = 0;  ///< shear correction coefficient
  double loss_factor = 0;  ///< structural damping eta (E -> E (1 + i eta)) for FRFs
};

/// Beam: length L along x, rectangular section width (y) x height (z).
/// Plate: a = length (x), b = width (y), thickness h = height.
/// Largest half-wave counts (m along a, n along b) among the first k modes of a simply supported
/// a x b plate (ordered by (m/a)^2 + (n/b)^2): what a mesh must resolve for k modes of any plate.
std::pair<int, int> plate_half_waves(double a, double b, int k);

/// The shape of a beam's cross-section (`[geometry] section = { shape = ... }`).
enum class SectionShape {
  Rectangle,  ///< width (y) x height (z): geometry.width, geometry.height (today's keys are its shorthand)
  Circle,     ///< solid, diameter
  Tube,       ///< outer_diameter, inner_diameter (thick or thin walled)
  General,    ///< given A, Iy, Iz, J (the shape itself unknown)
};
std::string to_string(SectionShape);

/// A beam's cross-section as written (Scene::cross_section). Circles and tubes also set
/// geometry.width = height = the outer diameter, and a general section the sides of the rectangle
/// with its A and Iy (height = sqrt(12 Iy / A), width = A / height): the section's extent, for
/// sizes only (probes across it, slenderness), never for its properties, which Scene::section()
/// computes from this.
struct SectionSpec {
  SectionShape shape = SectionShape::Rectangle;
  double diameter = 0;        ///< circle: diameter; tube: outer diameter, m
  double inner_diameter = 0;  ///< tube, m (0 < inner < outer)
  double A = 0, Iy = 0, Iz = 0, J = 0;  ///< general: m^2, m^4, m^4, m^4
};

struct Geometry {
  double length = 0, width = 0, height = 0;
};

/// Rectangular-section properties derived from Geometry.
struct Section {
  double A;   ///< area, m^2
  double Iy;  ///< second moment about y (bending in x-z), m^4
  double Iz;  ///< second moment about z (bending in x-y), m^4
  double J;   ///< Saint-Venant torsion constant, m^4
  double Ip;  ///< polar second moment Iy + Iz (torsional rotary inertia per rho), m^4
};
Section rectangular_section(double width, double height);
/// Solid circle of diameter d: A = pi d^2 / 4, Iy = Iz = pi d^4 / 64, J = Ip = pi d^4 / 32.
Section circular_section(double d);
/// Tube of outer and inner diameters D > d >= 0: the circle's formulas with D^n - d^n.
Section tube_section(double D, double d);
/// The section's properties (A, Iy, Iz, J, Ip = Iy + Iz) for any shape (a rectangle: g's width
/// and height).
Section section_properties(const Geometry& g, const SectionSpec& spec);
/// Cowper's shear coefficient (J. Appl. Mech. 33, 1966) of a solid circle, 6 (1 + nu) / (7 + 6 nu),
/// and of a tube with m = d / D, 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2).
double cowper_kappa_tube(double nu, double m);

/// How a tapered piece's dimensions vary from their start value d0 to their end value d1 over its
/// length l (`profile`): linear, d(s) = d0 + (d1 - d0) s / l; exponential, d(s) = d0 (d1 / d0)^(s / l).
enum class Profile { Linear, Exponential };
std::string to_string(Profile);

/// A tapered piece's section at its end x_to (`[start, end]` dimensions in [[segments]]): the
/// rectangle's sides and the section's dimensions there, and how each varies between the ends.
/// A dimension written as one number has the same value at both ends.
struct SectionEnd {
  double width = 0, height = 0;
  SectionSpec section;
  Profile profile = Profile::Linear;
};

/// One piece of a stepped beam (`[[segments]]`): over [x_from, x_to] (m), with its own section
/// (`width` x `height` for a rectangle, and the section's extent otherwise, as Geometry's) and its
/// own material (the scene's, with the keys the piece overrides). Scene::beam_pieces gives every
/// beam as such pieces. A tapered piece (`end`) has this section at x_from and `end`'s at x_to.
struct Segment {
  double x_from = 0, x_to = 0;
  double width = 0, height = 0;
  SectionSpec section;
  Material material;
  std::optional<SectionEnd> end;  ///< set for a tapered piece only
  /// A tube whose bore ratio varies with a default (Cowper's) shear coefficient: kappa_at follows it.
  bool kappa_follows_shape = false;

  bool tapered() const { return end.has_value(); }
  /// A uniform piece's section properties (throws std::logic_error for a tapered piece: use
  /// properties_at, or integrate over it).
  Section properties() const;
  /// The section properties at x (m, along the beam, clamped to [x_from, x_to]).
  Section properties_at(double x) const;
  /// The uniform piece over [x_from, x_to] with this piece's section (and shear coefficient) at x.
  Segment uniform_at(double x) const;
  /// The shear coefficient at x: the material's, or Cowper's for the local bore (kappa_follows_shape).
  double kappa_at(double x) const;
  /// Bounds over [x0, x1] of this piece (SectionBounds); a uniform piece's are its section.
  struct Bounds;
  Bounds bounds_on(double x0, double x1) const;
  double length() const { return x_to - x_from; }
  /// The piece's mass, kg: rho A l, or a tapered piece's integral of rho A(x) (8-point
  /// Gauss-Legendre on 16 parts: its area, a polynomial of degree <= 4 or an exponential, to rounding).
  double mass() const;
};

/// Over [x0, x1] of a piece: a section no stiffer than the piece anywhere there (`weakest`: each
/// property at most its lowest value there) and one no lighter (`heaviest`: each at least its
/// highest), and a shear coefficient no higher (`kappa_lo`). Each dimension varies monotonically
/// (linear or exponential), so its extremes lie at x0 and x1; every property grows with the outer
/// dimensions and falls with a tube's bore, and Cowper's tube coefficient falls as the bore ratio
/// grows (m^2 / (1 + m^2)^2 rises on [0, 1]). `weakest_exists` is false where the widest bore
/// reaches the narrowest outside over the stretch (the weakest section is then no section: cut it).
struct Segment::Bounds {
  Section weakest{}, heaviest{};
  double kappa_lo = 0;
  bool weakest_exists = true;
};

/// A static point load. Beam: at x. Plate: at (x, y); only Fz is meaningful.
struct PointLoad {
  double x = 0, y = 0;
  double Fx = 0, Fy = 0, Fz = 0;  ///< N
  double Mx = 0, My = 0, Mz = 0;  ///< N*m, right-handed about the axes
};

/// A support between a beam's ends, or inside a plate (`[[supports.points]]`): the springs of
/// `support` (a name or springs, as at the ends) acting at x on a beam's axis, at (x, y) on a plate
/// (translational on w, rotational on both rotations).
struct PointSupport {
  double x = 0, y = 0;
  Support support;
};

/// A point mass on a beam's axis at x, or on a plate at (x, y) (`[[masses]]`), rigidly attached:
/// mass, kg, and rotary inertias about axes through the point parallel to x, y, z, kg m^2 (Jx polar;
/// Jy turns with the x-z bending rotation theta_y, Jz with theta_z).
struct PointMass {
  double x = 0, y = 0;
  double mass = 0;
  double Jx = 0, Jy = 0, Jz = 0;
};

/// A distributed load. Beam (`[[line_loads]]`): over x in [from[0], to[0]], N/m along +x, +y, +z,
/// each component varying linearly from its value at `from` (index 0) to its value at `to`
/// (index 1). Plate (`[[pressures]]`): a uniform pressure qz, Pa along +z, over the patch
/// [from[0], to[0]] x [from[1], to[1]].
struct DistributedLoad {
  std::array<double, 2> from{}, to{};
  std::array<double, 2> qx{}, qy{}, qz{};
  /// Beams only: a smooth factor on the linear intensities (the weight of a tapered piece: its
  /// area at x over the area at x_from). Empty: 1.
  std::function<double(double)> factor;
  /// A beam component's intensity at x in [from[0], to[0]].
  double at(const std::array<double, 2>& q, double x) const {
    const double t = (x - from[0]) / (to[0] - from[0]);
    return (q[0] + (q[1] - q[0]) * t) * (factor ? factor(x) : 1.0);
  }
};
/// Gauss-Legendre points and weights that integrate a beam load's intensity over [lo, hi], and its
/// moment about any point: two points for a linear intensity (exact); for one with a factor, 8
/// points on each of `parts` equal parts (exact to degree 15 on each part: the factors of tapered
/// pieces, polynomials of degree <= 4, exactly, and their exponentials to rounding).
std::vector<std::pair<double, double>> load_gauss_points(const DistributedLoad& q, double lo, double hi,
                                                         int parts = 16);

struct FrfRequest {
  std::array<double, 2> excite{};   ///< beam: {x, 0}; plate: {x, y}; unit Fz there
  std::array<double, 2> observe{};  ///< where w is observed
  double omega_min = 0, omega_max = 0;  ///< rad/s
  int points = 0;
};

/// Where mode shapes are sampled: nx evenly spaced points along x (both ends included), and ny
/// across a plate's width (1 for a beam). `[request] shapes = true` gives the defaults.
struct ShapeRequest {
  int nx = 0, ny = 1;
  /// Where given (in code only: the transient response's load quadrature and probes), the points
  /// sampled instead of the nx x ny grid.
  std::vector<std::array<double, 2>> points{};
  /// Also the modes' bending moments My at the points (ModeShapes::moments), where the back-end
  /// gives them (in code only: the transient response's moment histories).
  bool moments = false;
  static constexpr int kBeamDefaultNx = 41, kPlateDefaultNx = 21, kPlateDefaultNy = 13;
};

/// `[request.transient]`: the time history of the scene's static loads (all of them, gravity
/// included) times a time function g(t), from rest at t = 0, by modal superposition.
struct TransientRequest {
  double duration = 0;  ///< s
  double step = 0;      ///< output step, s
  /// g(t): step (1 for t > 0), impulse (the loads are impulses, N s, at t = 0), ramp (t / rise up to
  /// rise, then 1), harmonic (sin(omega t)), table (piecewise linear through time/factor, the last
  /// factor held after the last time).
  enum class Load { Step, Impulse, Ramp, Harmonic, Table };
  Load load = Load::Step;
  double rise = 0;   ///< ramp, s
  double omega = 0;  ///< harmonic, rad/s
  std::vector<double> time, factor;  ///< table: ascending times from 0, s; factors
  /// Damping per mode: none; modal (the same ratio zeta for every mode); Rayleigh
  /// (C = alpha M + beta K: zeta_n = alpha / (2 omega_n) + beta omega_n / 2).
  enum class Damping { None, Modal, Rayleigh };
  Damping damping = Damping::None;
  double zeta = 0, alpha = 0, beta = 0;
  /// Mode acceleration: the truncated modes' static share (the statics minus the used modes'
  /// static part) added quasi-statically.
  bool static_correction = true;
  /// A beam's bending moment histories My at the probes, where the back-end's modes carry moments.
  /// Added (the default, no `moments` key): given with their own truncation estimate and, where it
  /// exceeds the tolerance, a warning; they neither drive the modes used nor set the status (after
  /// a suddenly applied point load a moment series converges only like 1 / modes). Asked
  /// (`moments = true`): judged like w, their estimate driving the modes and the status. Off
  /// (`moments = false`): w and the rotations only.
  enum class Moments { Added, Asked, Off };
  Moments moments = Moments::Added;
};
std::string to_string(TransientRequest::Load);  ///< step, impulse, ramp, harmonic, table

struct Request {
  int modes = 0;
  /// beam: {x, 0}; plate: {x, y}; frame: one per probe of Frame::probes (its global x and z).
  std::vector<std::array<double, 2>> probes;
  std::optional<FrfRequest> frf;
  std::optional<ShapeRequest> shapes;  ///< absent: no shapes are computed (nor paid for)
  std::optional<TransientRequest> transient;  ///< absent: no time history
  /// Relative accuracy asked of a discretized result: a back-end with a mesh estimates its own
  /// discretization error (Richardson against a second, coarser mesh) and a result whose
  /// estimate exceeds this is `not-converged` (frequencies; deflections relative to the largest).
  double tolerance = 1e-3;
};

/// A back-end option as written in the scene (`[backend.NAME]` key = value), as text: the
/// back-end's OptionSpec validates it when it solves (Solver::solve).
/// `[rotor]`: the beam is a shaft spinning about +x (physics "lateral"), and its whirl is asked at
/// each of the spin speeds (the Campbell diagram, Result::campbell).
struct Rotor {
  std::vector<double> spin;  ///< rad/s, >= 0, ascending
  /// The frame the whirl is seen from: the ground's (stationary: gyroscopic terms only; needs an
  /// axisymmetric shaft), or the shaft's own (rotating: Coriolis and spin softening; asymmetric
  /// sections allowed).
  enum class Frame { Stationary, Rotating };
  Frame frame = Frame::Stationary;
};
std::string to_string(Rotor::Frame);  ///< stationary, rotating

struct SceneOption {
  std::string key;
  std::string text;
};

struct Frame;  // frame.hpp: a frame's nodes, members and what acts on them

struct Scene {
  std::string name;
  std::string source;  ///< file it was read from (for messages)
  SceneKind kind = SceneKind::Beam;
  Physics physics = Physics::Bending;
  Theory theory = Theory::Timoshenko;
  Geometry geometry;
  SectionSpec cross_section;  ///< a beam's `[geometry] section`; plates: a rectangle (width, thickness)
  Material material;
  /// Beam: ends x0, xL. Plate: edges x0, xL (normal x), y0, yB (normal y).
  Support x0, xL, y0, yB;
  /// Beams: the pieces of a stepped beam, from x = 0 to the length, in order (empty: uniform, the
  /// section and material above). When given, geometry.width and height are the largest extent
  /// over the pieces and cross_section / material are the first piece's: use beam_pieces().
  std::vector<Segment> segments;
  std::vector<PointSupport> point_supports;  ///< beams: between the ends, by ascending x; plates: as written
  std::vector<PointMass> masses;             ///< beams: by ascending x; plates: as written
  std::vector<PointLoad> loads;
  std::vector<DistributedLoad> line_loads;  ///< beams
  std::vector<DistributedLoad> pressures;   ///< plates
  /// [gravity] g, m/s^2: the self-weight of the structure (rho A g per length of a beam, rho h g_z
  /// per area of a plate) and of its point masses (m g at each).
  std::optional<std::array<double, 3>> gravity;
  Request request;
  std::optional<Rotor> rotor;  ///< `[rotor]` (beams of physics "lateral" only)
  std::vector<std::string> notes;  ///< defaults applied, errata cited, etc.
  /// [backend.NAME] tables, by back-end name (names checked against the registry by the caller).
  std::map<std::string, std::vector<SceneOption>> backend_options;
  /// A frame's nodes, members, supports, masses, loads and probes (kind frame only; frame.hpp).
  /// Shared and immutable once read: copies of the scene see the same frame.
  std::shared_ptr<const Frame> frame;

  bool is_beam() const { return kind == SceneKind::Beam; }
  bool is_plate() const { return kind == SceneKind::Plate; }
  bool is_frame() const { return kind == SceneKind::Frame; }
  Section section() const { return section_properties(geometry, cross_section); }
  /// A beam's pieces: `segments`, or the uniform beam as one piece over [0, length].
  std::vector<Segment> beam_pieces() const;
  /// A stepped beam (more than one piece).
  bool is_stepped() const { return segments.size() > 1; }
  /// Whether any piece's section varies along it (Segment::tapered).
  bool has_tapered_pieces() const;
  /// Every point load: `loads` and, under gravity, the weight of each point mass (m g at its x).
  std::vector<PointLoad> all_point_loads() const;
  /// Every distributed load: `line_loads` (beam) or `pressures` (plate) and, under gravity, the
  /// structure's own weight over the whole of it.
  std::vector<DistributedLoad> all_distributed_loads() const;
  /// Plate flexural rigidity D = E h^3 / (12 (1 - nu^2)), N*m.
  double plate_D() const;
  /// The points where shapes are sampled (request.shapes; empty without it): beam {x_i, 0},
  /// plate {x_i, y_j} with x fastest.
  std::vector<std::array<double, 2>> shape_points() const;
  /// The components of a shape, as dofs indices 0..5 (u, v, w, theta_x, theta_y, theta_z): beam
  /// bending {w, theta_y}; planar {u, w, theta_y}; spatial all six; lateral {v, w, theta_y, theta_z};
  /// plate {w, theta_x, theta_y}.
  std::vector<int> shape_components() const;
};

/// The rigid-body motions of a plate that its edge supports leave free, by name (translation z,
/// rotation about x, rotation about y; several named as one combination where they are tied
/// together), from the supports' pattern alone (no stiffness is compared: 1e-300 N/m restrains).
/// An edge with a translational spring ties w along it; one with a rotational spring, the slope
/// across it. Empty for beams and for restrained plates.
std::vector<std::string> free_plate_rigid_motions(const Scene& scene);

/// The largest scene file read (a scene is a few kB; anything this large is not one).
inline constexpr std::uintmax_t kMaxSceneBytes = 1u << 20;
/// Reads and validates a scene file: a regular file of at most kMaxSceneBytes. Throws InputError
/// (file, key, reason), naming what the path is when it is not a scene file.
Scene load_scene(const std::filesystem::path& path);
/// Parses and validates TOML text; `source` names it in messages.
Scene parse_scene(std::string_view toml_text, const std::string& source);
/// Checks a scene built in code with the same rules as the parser.
void validate(const Scene& scene);

}  // namespace modalbench
