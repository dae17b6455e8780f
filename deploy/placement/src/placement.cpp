#include "wbi/deploy/placement.hpp"

namespace wbi::deploy {

void read_join_options(const std::string& file, const std::string& identity,
                       dds::ParticipantOptions& options) {
  apply_join_keys(read_deploy_file(file).join, identity, options);
}

}  // namespace wbi::deploy
