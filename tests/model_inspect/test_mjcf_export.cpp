// mjcf_export_from_urdf / mjcf_body_count / write_export_summary / save_text_file
// on the project's humanoid and arm: the body count is what the writer writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model_inspect/mjcf_export.hpp>

#include "test_support.hpp"

namespace wm = wbi::model;
namespace inspect = wbi::model_inspect;

namespace {

std::string model_file(const char* file) { return wbi::test::project_model(file).string(); }

// Occurrences of "<body " in the MJCF: the bodies besides the world.
int bodies_in(const std::string& xml) {
  int count = 0;
  for (auto at = xml.find("<body "); at != std::string::npos; at = xml.find("<body ", at + 1)) {
    ++count;
  }
  return count;
}

}  // namespace

TEST(MjcfExport, FromUrdfIsTheLoadedModelWithRepairOnAndDefaultOptions) {
  wm::LoadOptions load;
  load.fixed_base = true;
  const inspect::MjcfExport exported =
      inspect::mjcf_export_from_urdf(model_file("humanoid.urdf"), load);
  const wm::Model reference = wm::load_urdf_file(model_file("humanoid.urdf"), load);
  EXPECT_FALSE(exported.model.floating_base);  // the caller's options are kept
  EXPECT_EQ(exported.model.joint_name, reference.joint_name);
  EXPECT_EQ(exported.model.n_bodies, reference.n_bodies);
  EXPECT_TRUE(
      exported.model.repaired_inertia_links.empty());  // the project's inertias are physical
  EXPECT_TRUE(exported.options.welded_links.empty());
  EXPECT_EQ(exported.options.timestep, wbi::mjcf::MjcfOptions{}.timestep);
}

TEST(MjcfExport, BodyCountIsWhatTheWriterWritesAlsoWithWeldedLinks) {
  inspect::MjcfExport exported = inspect::mjcf_export_from_urdf(model_file("humanoid.urdf"), {});
  EXPECT_EQ(inspect::mjcf_body_count(exported), exported.model.n_bodies);
  EXPECT_EQ(bodies_in(wbi::mjcf::write_mjcf(exported.model, exported.options)),
            inspect::mjcf_body_count(exported));
  // The feet below the F/T sensors' fixed joints, as bodies of their own.
  exported.options.welded_links = {"l_foot", "r_foot"};
  EXPECT_EQ(inspect::mjcf_body_count(exported), exported.model.n_bodies + 2);
  EXPECT_EQ(bodies_in(wbi::mjcf::write_mjcf(exported.model, exported.options)),
            inspect::mjcf_body_count(exported));
}

TEST(MjcfExport, SummaryNamesTheModelAndItsSizes) {
  const inspect::MjcfExport arm = inspect::mjcf_export_from_urdf(model_file("arm7.urdf"), {});
  std::ostringstream summary;
  inspect::write_export_summary(summary, arm);
  std::ostringstream mass;
  mass << arm.model.total_mass;
  EXPECT_EQ(summary.str(),
            arm.model.name + ", 7 joints, 8 bodies, fixed base, total mass " + mass.str() + " kg");
  const inspect::MjcfExport humanoid =
      inspect::mjcf_export_from_urdf(model_file("humanoid.urdf"), {});
  std::ostringstream floating;
  inspect::write_export_summary(floating, humanoid);
  EXPECT_NE(floating.str().find(", free-floating, "), std::string::npos) << floating.str();
}

TEST(MjcfExport, SaveTextFileWritesTheBytesOrNamesTheFile) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("wbi_inspect_export_" + std::to_string(::getpid()) + ".xml");
  const std::string text = "<mujoco>\n\t\xc2\xb5\n</mujoco>";  // a tab and a UTF-8 µ, kept as is
  inspect::save_text_file(text, path.string());
  std::ifstream in(path, std::ios::binary);
  std::ostringstream back;
  back << in.rdbuf();
  EXPECT_EQ(back.str(), text);
  std::filesystem::remove(path);
  try {
    inspect::save_text_file(text, "/no/such/dir/x.xml");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write '/no/such/dir/x.xml'");
  }
}
