// SPDX-License-Identifier: BSD-3-Clause
#include "lengths.hpp"

#include <cmath>
#include <cstdio>
#include <functional>

#include "camfollower/error.hpp"

namespace camfollower::config {

namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

// The length as the hint would write it in `unit` (the same digits, now with a unit).
std::string with_unit(const Length& L, const char* unit) {
    if (L.parts.empty()) return "\"" + number(L.value) + " " + unit + "\"";
    std::string out = "[";
    for (std::size_t i = 0; i < L.parts.size(); ++i)
        out += (i ? ", \"" : "\"") + number(L.parts[i]) + " " + unit + "\"";
    return out + "]";
}

// "did you mean "25 mm"?": the first of mm, um that makes the value plausible (`fits` of its value in
// metres), else a plain request for the unit. A value meant as metres keeps its unit: "25 m".
std::string hint(const Length& L, const std::function<bool(double)>& fits) {
    std::string out;
    for (const auto& [unit, factor] : {std::pair{"mm", 1e-3}, std::pair{"um", 1e-6}})
        if (fits(L.value * factor)) {
            out = "did you mean " + with_unit(L, unit) + "?";
            break;
        }
    if (out.empty()) out = "write it with its unit, e.g. " + with_unit(L, "mm");
    return out + " (a bare number is metres; write " + with_unit(L, "m") + " if you mean it)";
}

bool usable(double v) { return std::isfinite(v) && v > 0.0; }

// What is wrong with L when it is bare and above `limit` m ("" if nothing); `why` says what the
// limit is ("10 x the base radius 0.04 m of contact 'cam'").
std::string above(const Length& L, const char* what, double limit, const std::string& why) {
    if (!L.bare || !std::isfinite(L.value) || !usable(limit) || std::abs(L.value) <= limit) return "";
    return detail::concat(what, " ", number(L.value), " m is more than ", why, ": ",
                          hint(L, [&](double v) { return std::abs(v) <= limit; }));
}

// The same, refused at L's key.
void refuse_above(const Length& L, const char* what, double limit, const std::string& why) {
    const std::string problem = above(L, what, limit, why);
    if (!problem.empty()) detail::fail(L.where, ": ", problem);
}

std::string ten_base_radii(const ContactLengths& c) {
    return std::string("10 x ") + c.size_name + " " + number(c.base_radius.value) + " m of " + c.owner;
}

}  // namespace

std::optional<Length>* ContactLengths::slot(std::string_view name) {
    if (name == "roller_radius") return &roller_radius;
    if (name == "offset") return &offset;
    if (name == "face_offset") return &face_offset;
    if (name == "arm_length") return &arm_length;
    if (name == "pivot") return barrel ? nullptr : &pivot;
    return nullptr;
}

std::string offset_problem(const ContactLengths& c) {
    if (!c.offset || !usable(c.base_radius.value)) return "";
    return above(*c.offset, "the offset", 10.0 * c.base_radius.value, ten_base_radii(c));
}

void check_follower_lengths(const ContactLengths& c, bool offset) {
    const Length& rb = c.base_radius;
    const std::string of = " of " + c.owner;
    if (!usable(rb.value)) return;  // the follower's own check names it
    // The base radius first: when it is the one written without its unit, the others look too small.
    refuse_above(rb, c.size_name, 1.0, "1 m (a cam that large is written with its unit)");
    if (c.roller_radius && usable(c.roller_radius->value))
        refuse_above(rb, c.size_name, 100.0 * c.roller_radius->value,
                     "100 x the roller radius " + number(c.roller_radius->value) + " m" + of);
    if (c.arm_length && usable(c.arm_length->value))
        refuse_above(rb, c.size_name, 10.0 * c.arm_length->value,
                     "10 x the arm length " + number(c.arm_length->value) + " m" + of);
    if (c.pivot && usable(c.pivot->value))
        refuse_above(rb, "the base radius", 10.0 * c.pivot->value,
                     "10 x the pivot's distance " + number(c.pivot->value) + " m from the cam centre" + of);
    const std::string ten = ten_base_radii(c);
    const std::string hundred = std::string("100 x ") + c.size_name + " " + number(rb.value) + " m" + of;
    if (c.roller_radius) refuse_above(*c.roller_radius, "the roller radius", 10.0 * rb.value, ten);
    if (c.offset && offset) refuse_above(*c.offset, "the offset", 10.0 * rb.value, ten);
    if (c.face_offset) refuse_above(*c.face_offset, "the face offset", 10.0 * rb.value, ten);
    if (c.arm_length) refuse_above(*c.arm_length, "the arm length", 100.0 * rb.value, hundred);
    if (c.pivot) refuse_above(*c.pivot, "the pivot's distance from the cam centre", 100.0 * rb.value, hundred);
}

void check_lift(const Length& lift, double base_radius, const std::string& owner) {
    if (!usable(base_radius)) return;
    refuse_above(lift, "the lift", 10.0 * base_radius,
                 "10 x the base radius " + number(base_radius) + " m of " + owner);
}

void check_arm_angle(const Length& lift, const std::string& owner) {
    if (!lift.bare || !std::isfinite(lift.value) || std::abs(lift.value) <= max_bare_arm_angle) return;
    detail::fail(lift.where, ": the arm's lift ", number(lift.value), " rad of ", owner,
                 " is more than a quarter turn (", number(max_bare_arm_angle), " rad): did you mean \"",
                 number(lift.value), " deg\"? (a bare number is radians; write \"", number(lift.value),
                 " rad\" if you mean it)");
}

void check_small_length(const Length& length, const char* what, double base_radius, const std::string& owner) {
    if (!usable(base_radius)) return;
    refuse_above(length, what, 0.1 * base_radius,
                 "a tenth of the base radius " + number(base_radius) + " m of " + owner);
}

}  // namespace camfollower::config
