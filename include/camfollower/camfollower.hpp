// camfollower: dynamics of flexible cam-follower mechanisms. Facade header: the whole public API.
#pragma once

#include "camfollower/contact/hertz.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/geometry/disk_cam.hpp"
#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/model/defects.hpp"
#include "camfollower/model/modal.hpp"
#include "camfollower/model/network.hpp"
#include "camfollower/model/parameters.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/solver/integrate.hpp"
#include "camfollower/solver/newmark.hpp"
#include "camfollower/solver/observers.hpp"
#include "camfollower/solver/simulate.hpp"
