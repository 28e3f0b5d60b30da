// navfn-smt: rclcpp/clock.hpp is part of the rclcpp stub.
#pragma once
#include "rclcpp/rclcpp.hpp"
