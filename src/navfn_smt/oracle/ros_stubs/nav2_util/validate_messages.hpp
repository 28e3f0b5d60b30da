// navfn-smt: nav2_util::validateMsg (Humble to Kilted): see nav2_ros_common/validate_messages.hpp.
#pragma once
#include "nav2_ros_common/validate_messages.hpp"
namespace nav2_util
{
using nav2::validateMsg;
}
