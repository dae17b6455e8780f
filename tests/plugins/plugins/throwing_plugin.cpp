// A plugin whose registration throws (a lab's check at load failed).
#include <stdexcept>

#include <wbi/plugin.hpp>

WBI_PLUGIN(/*catalog*/) { throw std::runtime_error("the lab's calibration file is missing"); }
