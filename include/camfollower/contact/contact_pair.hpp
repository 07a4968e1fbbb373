// SPDX-License-Identifier: BSD-3-Clause
// A cam-follower contact pair: a cam (its motion program and phase on the camshaft), a follower
// kinematics type, a contact law, and the DOFs it couples:
//   cam_x, cam_y   translation of the cam centre (ground frame), or ground
//   follower       the follower's own coordinate s (m along a translating axis, rad of an arm)
//   lateral        translation of a translating follower across its axis, or ground
//   cam_twist      the camshaft's twist at the cam (rad, relative to its rigid rotation), or ground
// Its penetration is linear in q with coefficients that depend on the cam angle only
// (contact_geometry.hpp):
//   delta = g(theta)^T q + delta0(theta),  g = n_x e_cam_x + n_y e_cam_y - n_x e_lateral - lever e_follower,
//   delta0 = lever s(theta),               theta = theta_drive(t) + phase (+ q_twist),
// for a follower whose DOF is its lift in the ground frame; a pair's follower map and frame
// (ContactPairSpec::follower_ratio, follower_offset, frame_angle) scale the follower's terms, shift
// s and turn n for the cam centre's.
// Without a twist DOF theta depends on time only (terms prepared once per step). With one the cam angle
// is a state: delta depends on q_twist through theta, the generalized force on the twist is the
// contact force's moment about the shaft axis, F d delta / d theta (virtual work), and the terms are
// evaluated at every force evaluation.
// An eccentric cam (contact/eccentricity.hpp) changes the time-only terms (exact geometry of the
// displaced profile) and may add time-only loads p(t) on the pair's DOFs (unbalance, or the paper's
// literal force). The paper's literal backlash (contact/paper_backlash.hpp) imposes the follower's
// offset and loads the guide DOF, a sixth role that takes only that load.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "camfollower/contact/eccentricity.hpp"
#include "camfollower/contact/groove.hpp"
#include "camfollower/contact/hertz.hpp"
#include "camfollower/contact/paper_backlash.hpp"
#include "camfollower/core/ground.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/barrel_roller.hpp"
#include "camfollower/follower/oscillating_flat.hpp"
#include "camfollower/follower/oscillating_roller.hpp"
#include "camfollower/follower/parameters.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/translating_flat.hpp"
#include "camfollower/follower/translating_roller.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/motion/speed_program.hpp"

namespace camfollower {

// Every follower type, the one list: a new type joins here. The config reader and the Python
// bindings take every alternative from its parameter description (follower/parameters.hpp); Python
// re-exports the class in python/camfollower/__init__.py.
using Follower =
    std::variant<TranslatingRoller, TranslatingFlat, OscillatingRoller, OscillatingFlat, BarrelRoller, BarrelArmRoller>;

namespace detail {
template <class... F>
constexpr bool check_follower_types(const std::variant<F...>*) {
    return (check_follower_parameters<F>() && ...);
}
static_assert(check_follower_types(static_cast<const Follower*>(nullptr)));
}  // namespace detail

inline const char* follower_type_name(const Follower& f) {
    return std::visit([](const auto& x) { return std::decay_t<decltype(x)>::type_name; }, f);
}
namespace detail {
template <class... F>
std::vector<std::string> type_names_of(const std::variant<F...>*) {
    return {F::type_name...};
}
}  // namespace detail
// Every type's name, in the order of Follower (config choices, messages).
inline std::vector<std::string> follower_type_names() {
    return detail::type_names_of(static_cast<const Follower*>(nullptr));
}
// Translating followers lift by a length (m), oscillating ones by the arm's rotation (rad).
template <class F>
bool is_translating(const F&) {
    return F::translating;
}
inline bool is_translating(const Follower& f) {
    return std::visit([](const auto& x) { return std::decay_t<decltype(x)>::translating; }, f);
}

// Barrel cams' followers (follower/barrel_roller.hpp): their profile is a developed groove.
inline bool is_barrel(const Follower& f) {
    return std::visit([](const auto& x) { return is_barrel_follower<std::decay_t<decltype(x)>>::value; }, f);
}

// The cam's size: a disk cam's base radius, a barrel cam's cylinder radius (m; size hints).
inline double cam_radius(const Follower& f) {
    return std::visit(
        [](const auto& x) {
            if constexpr (is_barrel_follower<std::decay_t<decltype(x)>>::value) return x.cylinder_radius();
            else return x.base_radius();
        },
        f);
}

struct ContactPairSpec {
    std::string name;
    MotionProgram program;
    Follower follower;
    HertzContact law;
    double phase = 0.0;  // rad: cam angle = drive angle + phase
    std::string cam_x = "ground", cam_y = "ground", follower_dof, lateral = "ground";
    CamEccentricity eccentricity;      // none by default
    std::string cam_twist = "ground";  // the shaft's twist DOF at the cam (ground: a rigid camshaft)
    PaperBacklash paper_backlash{};    // off by default
    std::optional<Groove> groove{};    // a face groove's outer flank (form closure); none: force-closed
    // How the follower's DOFs move this pair's follower, and where it sits around the cam (a second
    // roller on the same follower, contact/conjugate.hpp). The pair's follower coordinate is
    // s = follower_offset + follower_ratio * q_follower (m or rad as the lift; ratio finite, non-zero)
    // and its lateral one follower_ratio * q_lateral. frame_angle (rad): the pair's frame (its
    // follower's axis or pivot frame) turned from the ground frame about the cam axis; the cam angle
    // it sees stays the drive angle + phase (so the cam sits at phase + frame_angle on the shaft), and the
    // contact normal reaches cam_x, cam_y turned by it.
    double follower_ratio = 1.0, follower_offset = 0.0, frame_angle = 0.0;

    // The plain pair: the follower's DOF is its lift, in the ground frame.
    bool plain_mapping() const { return follower_ratio == 1.0 && follower_offset == 0.0 && frame_angle == 0.0; }

    // The roles in the order of require_distinct_roles' messages (and ContactPair's indices).
    static constexpr int role_count = 6;
    static constexpr const char* role_names[role_count] = {"cam_x",   "cam_y",     "follower_dof",
                                                           "lateral", "cam_twist", "paper_backlash.guide_dof"};
    // Each role is a coordinate of its own: two roles on one DOF would add two different kinematic
    // terms to the same coordinate and give meaningless forces.
    void require_distinct_roles() const {
        const std::string* roles[ContactPairSpec::role_count] = {&cam_x,   &cam_y,     &follower_dof,
                                                                 &lateral, &cam_twist, &paper_backlash.guide_dof};
        if (follower_dof == ground_name) detail::fail("contact '", name, "': follower_dof must be a DOF, not ground");
        for (int a = 0; a < ContactPairSpec::role_count; ++a)
            for (int b = 0; b < a; ++b)
                if (*roles[a] != ground_name && *roles[a] == *roles[b])
                    detail::fail("contact '", name, "': ", role_names[a], " and ", role_names[b], " both name DOF '",
                                 *roles[a], "'; each role needs a DOF of its own (or ground)");
    }
};

// The time-only terms of one pair at one instant: sparse g and its rate (up to four DOFs, and the
// paper backlash's guide DOF, where g is zero and only the load p acts).
struct ContactTerms {
    static constexpr int slots = 5;
    double theta = 0.0;  // cam angle, rad
    std::array<int, slots> dof{};
    std::array<double, slots> g{}, g_dot{};
    std::array<double, slots> g_theta{};  // d g / d theta
    int count = 0;
    double delta0 = 0.0, delta0_dot = 0.0;
    double delta0_theta = 0.0;  // d delta0 / d theta
    // With a twist DOF: its index and d delta / d theta at the last evaluated q (the moment arm of
    // the contact force about the shaft axis, m); twist = -1 on a rigid camshaft.
    int twist = -1;
    double moment_arm = 0.0;
    double cos_alpha = 1.0, sin_alpha = 0.0;
    std::array<double, slots> p{}, p_dot{};  // time-only external loads on the same slots, N, N/s
    bool loaded = false;                     // any p != 0
};

// A pair with its DOFs resolved to indices (-1: ground), ready for the time loop.
class ContactPair {
public:
    ContactPair(ContactPairSpec spec, int cam_x, int cam_y, int follower, int lateral, int twist = -1, int guide = -1)
        : spec_(std::move(spec)),
          cam_x_(cam_x),
          cam_y_(cam_y),
          follower_(follower),
          lateral_(lateral),
          twist_(twist),
          guide_(guide) {
        const std::string who = "contact '" + spec_.name + "'";
        if (follower_ < 0) detail::fail(who, ": follower_dof must be a DOF, not ground");
        spec_.require_distinct_roles();
        const int indices[ContactPairSpec::role_count] = {cam_x_, cam_y_, follower_, lateral_, twist_, guide_};
        for (int a = 0; a < ContactPairSpec::role_count; ++a)
            for (int b = 0; b < a; ++b)
                if (indices[a] >= 0 && indices[a] == indices[b])
                    detail::fail(who, ": ", ContactPairSpec::role_names[a], " and ", ContactPairSpec::role_names[b],
                                 " are the same DOF; each role needs a DOF of its own (or ground)");
        if (lateral_ >= 0 && !is_translating(spec_.follower))
            detail::fail(who, ": lateral is defined for translating followers only (",
                         follower_type_name(spec_.follower), ")");
        detail::require_positive(spec_.law.stiffness, (who + " contact stiffness").c_str(), "(N/m^n)");
        detail::require_in_range(spec_.law.exponent, 1.0, 3.0, (who + " contact exponent").c_str());
        detail::require_non_negative(spec_.law.damping_factor, (who + " contact damping factor").c_str(), "(s/m)");
        detail::require_finite(spec_.phase, (who + " phase").c_str());
        // The geometry must be followable: no undercut, no cusp, pressure angle below 90 deg.
        std::visit(
            [&](const auto& f) {
                try {
                    check_undercut(spec_.program, f);
                } catch (const std::invalid_argument& e) {
                    detail::fail(who, ": ", e.what());
                }
            },
            spec_.follower);
        const CamEccentricity& ecc = spec_.eccentricity;
        ecc.validate(who);
        if (ecc.any() && is_barrel(spec_.follower))
            detail::fail(who, ": eccentricity is modelled for disk cams; a barrel cam's (",
                         follower_type_name(spec_.follower), ") is not");
        if (twist_ >= 0 && ecc.paper_force() && ecc.any())
            detail::fail(who, ": the paper's eccentricity force (", eccentricity_formulation_name(ecc.formulation),
                         ") is not defined on a twisting camshaft; use 'exact'");
        if (ecc.paper_force() && ecc.any()) {
            if (!is_translating(spec_.follower))
                detail::fail(who, ": the paper's eccentricity force (", eccentricity_formulation_name(ecc.formulation),
                             ") acts along a translating follower's axis; use 'exact' for ",
                             follower_type_name(spec_.follower));
            if (ecc.formulation != EccentricityFormulation::paper_force_roller && cam_y_ < 0)
                detail::fail(who, ": ", eccentricity_formulation_name(ecc.formulation),
                             " loads the camshaft, so cam_y must be a DOF, not ground");
        }
        if (ecc.unbalance_mass > 0.0 && cam_x_ < 0 && cam_y_ < 0)
            detail::fail(who, ": an unbalance mass loads the cam centre, so cam_x or cam_y must be a DOF");
        check_paper_backlash(who);
        if (spec_.groove) check_groove(who);
        check_mapping(who);
        // Where each role's coefficient goes in the sparse g (the guide's is zero: a load only).
        const int roles[ContactTerms::slots] = {cam_x_, cam_y_, lateral_, follower_, guide_};
        for (int r = 0; r < ContactTerms::slots; ++r) {
            slot_[r] = -1;
            if (roles[r] < 0) continue;
            for (int i = 0; i < count_; ++i)
                if (dofs_[i] == roles[r]) slot_[r] = i;
            if (slot_[r] < 0) dofs_[count_] = roles[r], slot_[r] = count_++;
        }
        // The displaced profile must be followable all the way round (the shape is unchanged, so
        // undercut is not affected; the pressure angle and the roller's position are).
        if (ecc.any() && !ecc.paper_force())
            for (int i = 0; i < 720; ++i) {
                const double theta = two_pi * i / 720.0;
                const ContactGeometry k = geometry(theta);
                if (!(std::abs(k.pressure_angle()) < 0.5 * pi) || !std::isfinite(k.lift))
                    detail::fail(who, ": with eccentricity radius ", ecc.radius, " m the pressure angle reaches ",
                                 radians_to_degrees(k.pressure_angle()), " deg at theta = ", radians_to_degrees(theta),
                                 " deg (must stay below 90 deg)");
            }
    }

    const ContactPairSpec& spec() const { return spec_; }
    const std::string& name() const { return spec_.name; }
    int twist() const { return twist_; }        // the twist DOF, -1 on a rigid camshaft
    int follower() const { return follower_; }  // the follower's DOF
    // The distinct DOFs of g (the twist not included).
    std::vector<int> dofs() const { return std::vector<int>(dofs_.begin(), dofs_.begin() + count_); }

    // The terms at time t on a rigid camshaft driven by `drive` (theta = drive angle + phase).
    void prepare(double t, const SpeedProgram& drive, ContactTerms& c) const {
        const DriveState d = drive.at(t);
        evaluate(d.angle + spec_.phase, d.rate, c, d.acceleration);
    }

    // The terms at cam angle theta turning at theta_rate (rad/s) and accelerating at
    // theta_acceleration (rad/s^2, loads of an unbalance only): on a twisting camshaft
    // theta = drive angle + phase + q_twist and theta_rate = drive rate + v_twist.
    void evaluate(double theta, double theta_rate, ContactTerms& c, double theta_acceleration = 0.0) const {
        const double omega = theta_rate;
        c.theta = theta;
        c.twist = twist_;
        const ContactGeometry k = geometry(c.theta);
        c.count = count_;
        c.dof = dofs_;
        c.g.fill(0.0), c.g_theta.fill(0.0);
        // The normal's ground components (the pair's frame turned by frame_angle) act on the cam centre;
        // the follower's coordinates enter through the pair's map s = offset + ratio q.
        const double ratio = spec_.follower_ratio, lift = k.lift - spec_.follower_offset;
        const double g[4] = {cos_frame_ * k.normal.x() - sin_frame_ * k.normal.y(),
                             sin_frame_ * k.normal.x() + cos_frame_ * k.normal.y(), -ratio * k.normal.x(),
                             -ratio * k.lever};
        const double g_theta[4] = {cos_frame_ * k.dnormal.x() - sin_frame_ * k.dnormal.y(),
                                   sin_frame_ * k.dnormal.x() + cos_frame_ * k.dnormal.y(), -ratio * k.dnormal.x(),
                                   -ratio * k.dlever};
        for (int i = 0; i < 4; ++i)
            if (slot_[i] >= 0) c.g[slot_[i]] += g[i], c.g_theta[slot_[i]] += g_theta[i];
        for (int i = 0; i < ContactTerms::slots; ++i) c.g_dot[i] = omega * c.g_theta[i];
        c.delta0 = k.lever * lift;
        c.delta0_theta = k.dlever * lift + k.lever * k.dlift;
        c.cos_alpha = k.cos_alpha, c.sin_alpha = k.sin_alpha;
        const CamEccentricity& ecc = spec_.eccentricity;
        c.loaded = false;
        c.p.fill(0.0), c.p_dot.fill(0.0);
        c.delta0_dot = omega * c.delta0_theta;
        if (spec_.paper_backlash.any()) add_backlash_load(omega, c);
        if (!ecc.any()) return;
        const Eigen::Vector2d u = ecc.offset(c.theta), du = ecc.offset_rate(c.theta);
        if (!ecc.paper_force() && !std::holds_alternative<TranslatingRoller>(spec_.follower)) {
            // n . u: exact for flat faces, first order for the oscillating roller.
            c.delta0 += k.normal.dot(u);
            c.delta0_theta += k.dnormal.dot(u) + k.normal.dot(du);
        }
        c.delta0_dot = omega * c.delta0_theta;
        // Loads along +q of each role, and their time rates (d/dt = omega d/dtheta). The unbalance at
        // u(theta) loads the cam centre with m (omega^2 u - theta'' du); the rates keep theta'' but
        // leave out its own rate (they only set the quasi-static start).
        double p[4] = {0.0, 0.0, 0.0, 0.0}, p_dot[4] = {0.0, 0.0, 0.0, 0.0};
        const double m_u = ecc.unbalance_mass, centrifugal = m_u * omega * omega;
        const double tangential = m_u * theta_acceleration,
                     rate_of_centrifugal = 2.0 * m_u * omega * theta_acceleration;
        p[0] = centrifugal * u.x() - tangential * du.x();
        p[1] = centrifugal * u.y() - tangential * du.y();
        p_dot[0] = omega * centrifugal * du.x() + (rate_of_centrifugal + omega * tangential) * u.x();
        p_dot[1] = omega * centrifugal * du.y() + (rate_of_centrifugal + omega * tangential) * u.y();
        if (ecc.paper_force()) {
            const double F = spec_.law.stiffness * u.y(), F_dot = omega * spec_.law.stiffness * du.y();
            const bool on_cam = ecc.formulation != EccentricityFormulation::paper_force_roller;
            const bool on_roller = ecc.formulation != EccentricityFormulation::paper_force_camshaft;
            if (on_cam) p[1] -= F, p_dot[1] -= F_dot;
            if (on_roller) p[3] += F, p_dot[3] += F_dot;
        }
        for (int r = 0; r < 4; ++r)
            if (slot_[r] >= 0 && (p[r] != 0.0 || p_dot[r] != 0.0)) {
                c.p[slot_[r]] += p[r], c.p_dot[slot_[r]] += p_dot[r];
                c.loaded = true;
            }
    }

    // Amplitude of the paper's literal eccentricity force K_h epsilon (0 for the other formulations).
    double paper_force_amplitude() const {
        const CamEccentricity& ecc = spec_.eccentricity;
        return ecc.paper_force() ? spec_.law.stiffness * ecc.radius : 0.0;
    }

    // Contact geometry at cam angle theta: nominal, or the displaced profile's for a translating roller
    // on an eccentric cam (exact; the other followers add n . u in prepare()).
    ContactGeometry geometry(double theta) const {
        if (spec_.paper_backlash.any()) return backlash_geometry(theta);
        const CamEccentricity& ecc = spec_.eccentricity;
        if (ecc.any() && !ecc.paper_force())
            if (const auto* roller = std::get_if<TranslatingRoller>(&spec_.follower))
                return eccentric_contact(*roller, spec_.program, theta, ecc);
        const FollowerMotion m = spec_.program.evaluate(theta);
        return std::visit([&](const auto& f) { return f.contact(theta, m); }, spec_.follower);
    }

    template <class Vector>
    static double penetration(const ContactTerms& c, const Vector& q) {
        double d = c.delta0;
        for (int i = 0; i < c.count; ++i) d += c.g[i] * q[c.dof[i]];
        return d;
    }
    template <class Vector>
    static double penetration_rate(const ContactTerms& c, const Vector& q, const Vector& v) {
        double d = c.delta0_dot;
        for (int i = 0; i < c.count; ++i) d += c.g[i] * v[c.dof[i]] + c.g_dot[i] * q[c.dof[i]];
        return d;
    }
    // A grooved cam's outer flank: its clearance and contact law (the inner flank's when not given).
    bool grooved() const { return spec_.groove.has_value(); }
    double groove_clearance() const { return spec_.groove ? spec_.groove->clearance : 0.0; }
    const HertzContact& outer_law() const { return spec_.groove && spec_.groove->law ? *spec_.groove->law : spec_.law; }
    // The outer flank's response: penetration -delta - c, rate -delta' (contact/groove.hpp).
    ContactResponse outer_response(const ContactResponse& inner, double inner_rate) const {
        return outer_law()(-inner.delta - groove_clearance(), -inner_rate);
    }

private:
    // The follower map and frame: finite, a non-zero ratio; the formulations written for a follower
    // whose DOF is its lift in the ground frame refuse any other.
    void check_mapping(const std::string& who) {
        const double r = spec_.follower_ratio, phi = spec_.frame_angle;
        if (!(std::isfinite(r) && r != 0.0 && std::abs(r) <= 1e6 && std::abs(r) >= 1e-6))
            detail::fail(who, ": follower_ratio must be finite with 1e-6 <= |ratio| <= 1e6, got ", r);
        detail::require_finite(spec_.follower_offset, (who + " follower_offset").c_str());
        if (!(std::isfinite(phi) && std::abs(phi) <= 4.0 * pi))
            detail::fail(who, ": frame_angle must be in [-4 pi, 4 pi] rad, got ", phi);
        cos_frame_ = std::cos(phi), sin_frame_ = std::sin(phi);
        if (phi == 0.0) cos_frame_ = 1.0, sin_frame_ = 0.0;
        if (spec_.plain_mapping()) return;
        if (spec_.paper_backlash.any())
            detail::fail(who,
                         ": the paper backlash is written for a follower whose DOF is its lift in the ground "
                         "frame (follower_ratio 1, follower_offset 0, frame_angle 0)");
        if (spec_.eccentricity.any() && (phi != 0.0 || spec_.eccentricity.paper_force()))
            detail::fail(who, ": an eccentric cam (", eccentricity_formulation_name(spec_.eccentricity.formulation),
                         ") is modelled for a follower in the ground frame with its DOF as its lift (frame_angle 0",
                         spec_.eccentricity.paper_force() ? ", follower_ratio 1, follower_offset 0" : "", ")");
    }

    // A groove holds a roller: the clearance below its radius, the outer flank free of undercut. The
    // paper's literal backlash is the groove's clearance imposed as an offset: one or the other.
    void check_groove(const std::string& who) const {
        std::visit(
            [&](const auto& f) {
                using F = std::decay_t<decltype(f)>;
                if constexpr (std::is_same_v<F, TranslatingRoller> || std::is_same_v<F, OscillatingRoller> ||
                              is_barrel_follower<F>::value) {
                    spec_.groove->validate(who, f.roller_radius());
                    const auto curvature = [&](double theta) {
                        return f.pitch_curvature(spec_.program.evaluate(theta));
                    };
                    check_outer_flank(spec_.program, curvature, f.roller_radius() + spec_.groove->clearance, who);
                } else {
                    detail::fail(who, ": a groove holds a roller; ", F::type_name, " has none (use a roller follower)");
                }
            },
            spec_.follower);
        if (spec_.paper_backlash.any())
            detail::fail(who, ": the paper backlash and a groove both model the roller's clearance; use one");
    }

    // The paper backlash: a translating roller on a rigid camshaft, its offset +- b inside the pitch
    // circle, alone or with the paper's eccentricity force (the exact eccentric geometry has its own
    // offset).
    void check_paper_backlash(const std::string& who) {
        const PaperBacklash& b = spec_.paper_backlash;
        b.validate(who);
        if (!b.any()) {
            if (b.guide_stiffness != 0.0 || b.switch_width != 0.0)
                detail::fail(who, ": paper backlash switch_width and guide_stiffness need a backlash > 0");
            return;
        }
        const auto* roller = std::get_if<TranslatingRoller>(&spec_.follower);
        if (!roller)
            detail::fail(who, ": the paper backlash imposes a translating roller's offset; ",
                         follower_type_name(spec_.follower), " has none (model the guide's clearance instead)");
        if (twist_ >= 0) detail::fail(who, ": the paper backlash is not defined on a twisting camshaft");
        if (spec_.eccentricity.any() && !spec_.eccentricity.paper_force())
            detail::fail(who,
                         ": the paper backlash combines with the paper's eccentricity force only, not with 'exact' "
                         "(both move the roller's offset)");
        const double rp = roller->base_radius() + roller->roller_radius();
        if (!(std::abs(roller->offset()) + b.backlash < rp))
            detail::fail(who, ": paper backlash ", b.backlash, " m with |offset| = ", std::abs(roller->offset()),
                         " m make the offset reach ", std::abs(roller->offset()) + b.backlash,
                         " m: it must stay below base_radius + roller_radius = ", rp, " m");
        if (b.guide_stiffness > 0.0 && guide_ < 0)
            detail::fail(who, ": paper backlash guide_dof must be a DOF, not ground");
        backlash_side_ = BacklashSide(spec_.program, b.switch_width);
        for (int i = 0; i < 720; ++i) {
            const double theta = two_pi * i / 720.0;
            const ContactGeometry k = backlash_geometry(theta);
            if (!(std::abs(k.pressure_angle()) < 0.5 * pi))
                detail::fail(who, ": with paper backlash ", b.backlash, " m the pressure angle reaches ",
                             radians_to_degrees(k.pressure_angle()), " deg at theta = ", radians_to_degrees(theta),
                             " deg (must stay below 90 deg)");
        }
    }
    // The geometry at the imposed offset e' = e + b s(theta), its theta-derivatives total (the offset's
    // rate included): d alpha / d e' = (-R + (R' - e') e' / s0') / (R^2 + (R' - e')^2), R = s0' + h.
    ContactGeometry backlash_geometry(double theta) const {
        const auto& roller = std::get<TranslatingRoller>(spec_.follower);
        const BacklashSide::Value s = backlash_side_.at(theta);
        const double b = spec_.paper_backlash.backlash, e = roller.offset() + b * s.side;
        const TranslatingRoller shifted(roller.base_radius(), roller.roller_radius(), e);
        const FollowerMotion m = spec_.program.evaluate(theta);
        ContactGeometry k = shifted.contact(theta, m);
        if (s.dside != 0.0) {
            const double s0 = shifted.pitch_base(), R = s0 + m.h, p = m.dh - e;
            const double dalpha = (-R + p * e / s0) / (R * R + p * p) * b * s.dside;
            k.dnormal += Eigen::Vector2d(-k.cos_alpha, -k.sin_alpha) * dalpha;
            k.dlever -= k.sin_alpha * dalpha;
        }
        return k;
    }
    // The guide spring anchored on the displaced rod: K_rb b s(theta) along +guide_dof.
    void add_backlash_load(double omega, ContactTerms& c) const {
        if (guide_ < 0) return;
        const PaperBacklash& b = spec_.paper_backlash;
        const BacklashSide::Value s = backlash_side_.at(c.theta);
        const int slot = slot_[4];
        c.p[slot] += b.guide_stiffness * b.backlash * s.side;
        c.p_dot[slot] += omega * b.guide_stiffness * b.backlash * s.dside;
        c.loaded = true;
    }

    ContactPairSpec spec_;
    int cam_x_, cam_y_, follower_, lateral_, twist_, guide_;
    std::array<int, ContactTerms::slots> dofs_{}, slot_{};  // the distinct DOFs of g; slot of each role (-1: ground)
    int count_ = 0;
    BacklashSide backlash_side_;
    double cos_frame_ = 1.0, sin_frame_ = 0.0;
};

}  // namespace camfollower
