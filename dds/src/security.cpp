#include "security.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

namespace wbi::dds::detail {

namespace {

// "file:///absolute/path" (Fast DDS takes what follows "file://"), after checking that the file is
// there.
std::string file_uri(const std::filesystem::path& path, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw std::invalid_argument("DDS Security: no " + what + " at " + path.string() +
                                " (create them with scripts/wbi-security-setup)");
  }
  return "file://" + std::filesystem::absolute(path).string();
}

}  // namespace

void use_security(eprosima::fastdds::dds::DomainParticipantQos& qos,
                  const SecurityOptions& security) {
  if (!security.enabled()) {
    return;
  }
  if (security.identity.empty() || security.identity.find('/') != std::string::npos) {
    throw std::invalid_argument("DDS Security: the identity must be a name, got '" +
                                security.identity + "'");
  }
  const std::filesystem::path dir(security.directory);
  const std::filesystem::path mine = dir / security.identity;
  const std::string ca = file_uri(dir / "ca.pem", "CA certificate");
  const std::string certificate =
      file_uri(mine / "cert.pem", "certificate of identity '" + security.identity + "'");
  const std::string key = file_uri(mine / "key.pem", "key of identity '" + security.identity + "'");
  const std::string governance = file_uri(dir / "governance.p7s", "signed governance");
  const std::string permissions = file_uri(
      mine / "permissions.p7s", "signed permissions of identity '" + security.identity + "'");

  auto& properties = qos.properties().properties();
  auto set = [&](const std::string& name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", ca);
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", certificate);
  set("dds.sec.auth.builtin.PKI-DH.private_key", key);
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", ca);
  set("dds.sec.access.builtin.Access-Permissions.governance", governance);
  set("dds.sec.access.builtin.Access-Permissions.permissions", permissions);
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace wbi::dds::detail
