// SPDX-License-Identifier: BSD-3-Clause
// Implausible lengths: a bare number is metres, so a lift meant in millimetres and written `h = 25`
// reads as a 25 m lift. The lengths of one cam contact (its follower's geometry, the lift of its
// program, its eccentricity and profile errors) are compared with each other; a bare number far off
// the scale of the contact it sits in is refused at its key with a hint ("did you mean \"25 mm\"?").
// A length written with its unit ("25 m") is taken as written. The rules: docs/config.md, "Implausible
// lengths".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace camfollower::config {

// One length as the config wrote it.
struct Length {
    std::string where;          // "file:line: key.path" of the value (Section::where)
    double value = 0.0;         // m
    bool bare = false;          // a bare number (no unit): metres by the config's rule, and checked here
    std::vector<double> parts;  // a pivot's coordinates as written (value is their distance from the cam centre)
};

// The lengths of one contact. `owner` names it in messages ("contact 'cam'", "the paper preset's cam").
struct ContactLengths {
    std::string owner;
    Length base_radius;  // a barrel cam's: its cylinder radius
    std::optional<Length> roller_radius, offset, face_offset, arm_length, pivot;
    const char* size_name = "the base radius";  // "the cylinder radius" for a barrel cam
    bool barrel = false;  // a barrel cam's pivot is placed from the follower's station, not the cam centre

    // The slot of the follower parameter `name` (its config key), or nullptr for a length these rules
    // do not know (taken as written) and for base_radius, which is always present.
    std::optional<Length>* slot(std::string_view name);
};

// Refuses (std::invalid_argument at the value's key) a bare length of the follower that is implausible
// next to the contact's others: the base radius above 1 m, or above 100 x the roller radius, or above
// 10 x the arm length or the pivot's distance; a roller radius, offset or face offset above 10 x the
// base radius; an arm length or pivot distance above 100 x the base radius. Values that are not finite
// and positive are left to the model's own checks. With `offset` false the offset is not checked (see
// offset_problem).
void check_follower_lengths(const ContactLengths& c, bool offset = true);

// What is wrong with a bare offset by the rule above, with its hint ("" if nothing): the model refuses
// an offset beyond the base and roller radii with its own message, which this extends.
std::string offset_problem(const ContactLengths& c);

// A bare lift of a translating follower's program above 10 x the base radius `base_radius` (m) of the
// contact `owner` that uses it, refused at its key.
void check_lift(const Length& lift, double base_radius, const std::string& owner);

// An oscillating follower's lift (an arm angle) written as a bare number above a quarter turn: radians
// by the config's rule, but a swing that large is the degrees of a "15" meant as "15 deg". Refused at
// its key with the hint; written with its unit ("100 deg", "2 rad") it is taken as written.
inline constexpr double max_bare_arm_angle = 1.5707963267948966;  // rad: pi / 2
void check_arm_angle(const Length& lift, const std::string& owner);

// A bare eccentricity radius, waviness amplitude or dent depth (`what`) above a tenth of the base radius.
void check_small_length(const Length& length, const char* what, double base_radius, const std::string& owner);

}  // namespace camfollower::config
