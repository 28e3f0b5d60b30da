// navfn-smt: included by the inflation layers; they use nothing of it here.
#pragma once
#include "rclcpp/rclcpp.hpp"
