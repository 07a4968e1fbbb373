// camfollower: dynamics of flexible cam-follower mechanisms. Facade header: the whole public API.
#pragma once

#include "camfollower/error.hpp"
#include "camfollower/geometry/disk_cam.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/program.hpp"
