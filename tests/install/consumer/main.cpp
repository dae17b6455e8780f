// Uses the installed wbi as a controller project would: the whole-body
// interface through the DDS proxy, and the PD + gravity controller. With no
// robot running, init() must time out naming the missing components.
#include <iostream>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds_interface.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer URDF\n";
    return 2;
  }
  wbi::DdsInterfaceOptions options;
  options.robot = "nobody";
  options.urdf = argv[1];
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints({"joint_1", "joint_2"});
  try {
    robot->init(std::chrono::milliseconds(200));
  } catch (const wbi::TimeoutError& e) {
    std::cout << "consumer: ok (" << e.what() << ")\n";
    return 0;
  }
  std::cerr << "consumer: init succeeded without a robot\n";
  return 1;
}
