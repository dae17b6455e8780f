// Entry points of the verbs, one file each in this folder.
#pragma once

#include "../verb.hpp"

namespace wbi::cli {

int run_bag(Args args);
int run_bridge(Args args);
int run_controller(Args args);
int run_estimate(Args args);
int run_events(Args args);
int run_launch(Args args);
int run_model(Args args);
int run_param(Args args);
int run_play(Args args);
int run_plugins(Args args);
int run_render(Args args);
int run_record(Args args);
int run_robot(Args args);
int run_topic(Args args);

}  // namespace wbi::cli
