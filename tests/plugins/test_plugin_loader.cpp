// The plugin loader against real shared libraries (tests/plugins/plugins): the
// built-in plugin, a lab's plugin, and each way a plugin is refused, each
// refusal one line that names the file.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include <wbi/catalog.hpp>
#include <wbi/controllers/controller.hpp>
#include <wbi/plugin.hpp>
#include <wbi/runtime/plugins.hpp>
#include <wbi/runtime/registry.hpp>
#include <wbi/sim_robot/engine_registry.hpp>

namespace {

namespace fs = std::filesystem;
using wbi::runtime::PluginError;

fs::path test_plugin(const std::string& name) {
  return fs::path(WBI_TEST_PLUGIN_DIR) / ("libwbi_test_" + name + ".so");
}

// The refusal of loading `name` (after the built-in plugin), or "" when it loaded.
std::string refusal(const std::string& name) {
  wbi::Catalog catalog;
  try {
    wbi::runtime::load_plugins(catalog, {test_plugin(name).string()});
  } catch (const PluginError& e) {
    return e.what();
  }
  return "";
}

void expect_one_line_naming(const std::string& text, const fs::path& file) {
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  EXPECT_NE(text.find(file.string()), std::string::npos) << text;
}

TEST(PluginLoader, BuiltinPluginBringsTheProjectsTypes) {
  wbi::Catalog catalog;
  const auto loaded = wbi::runtime::load_plugins(catalog, {});
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(wbi::runtime::plugin_name(loaded[0]), "wbi_builtin");
  const auto& components = catalog.registry<wbi::runtime::Registry>();
  for (const char* type : {"sim_robot", "estimator", "model_service", "controller_host",
                           "com_sinusoid", "idle", "pd_gravity", "momentum_balance"}) {
    ASSERT_TRUE(components.contains(type)) << type;
    EXPECT_EQ(components.provider(type), loaded[0].string()) << type;
  }
  const auto& controllers = catalog.registry<wbi::controllers::ControllerRegistry>();
  EXPECT_TRUE(controllers.contains("pd_gravity"));
  EXPECT_TRUE(controllers.contains("momentum_balance"));
  EXPECT_TRUE(controllers.contains("walking_planner"));
  EXPECT_FALSE(controllers.contains("hold")) << "hold is the controller host's own";
  EXPECT_TRUE(catalog.registry<wbi::sim_robot::EngineRegistry>().contains("wbi"));
}

TEST(PluginLoader, LabPluginTypesComeFromIt) {
  wbi::Catalog catalog;
  const fs::path good = test_plugin("good");
  const auto loaded = wbi::runtime::load_plugins(catalog, {good.string()});
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded[1], good);
  const auto& controllers = catalog.registry<wbi::controllers::ControllerRegistry>();
  ASSERT_TRUE(controllers.contains("test_zero"));
  EXPECT_EQ(controllers.provider("test_zero"), good.string());
  EXPECT_NE(controllers.create("test_zero"), nullptr);
  const auto& components = catalog.registry<wbi::runtime::Registry>();
  EXPECT_EQ(components.provider("test_quiet"), good.string());
  // Its controller is also a one-controller host, made once every plugin was
  // in, and attributed to the plugin that brought the controller.
  ASSERT_TRUE(components.contains("test_zero"));
  EXPECT_EQ(components.provider("test_zero"), good.string());
  const std::string listing = wbi::runtime::describe_catalog(catalog);
  EXPECT_NE(listing.find("test_zero"), std::string::npos) << listing;
  EXPECT_NE(listing.find("wbi_test_good"), std::string::npos) << listing;
}

TEST(PluginLoader, SameFileTwiceIsLoadedOnce) {
  wbi::Catalog catalog;
  const fs::path good = test_plugin("good");
  const auto loaded = wbi::runtime::load_plugins(catalog, {good.string(), good.string()});
  EXPECT_EQ(loaded.size(), 2u);  // the built-in one and the lab's, once
}

TEST(PluginLoader, NameSearchedInPluginPathThenNearFolder) {
  const fs::path folder = test_plugin("good").parent_path();
  ::setenv(wbi::runtime::kPluginPathVariable, ("/nonexistent:" + folder.string()).c_str(), 1);
  EXPECT_EQ(wbi::runtime::find_plugin("wbi_test_good"), test_plugin("good"));
  ::unsetenv(wbi::runtime::kPluginPathVariable);
  // Beside the file that names it, and by a path relative to that file's folder.
  EXPECT_EQ(wbi::runtime::find_plugin("wbi_test_good", folder), test_plugin("good"));
  EXPECT_EQ(wbi::runtime::find_plugin("./libwbi_test_good.so", folder), test_plugin("good"));
}

TEST(PluginLoader, MissingNameListsTheFoldersSearched) {
  ::setenv(wbi::runtime::kPluginPathVariable, "/first/folder", 1);
  try {
    wbi::runtime::find_plugin("lab_without_build");
    FAIL() << "found a plugin that does not exist";
  } catch (const PluginError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("'lab_without_build': not found"), std::string::npos) << text;
    EXPECT_NE(text.find("liblab_without_build.so"), std::string::npos) << text;
    EXPECT_NE(text.find("/first/folder"), std::string::npos) << text;
    EXPECT_NE(text.find("wbi/plugins"), std::string::npos) << text;  // the program's own
  }
  ::unsetenv(wbi::runtime::kPluginPathVariable);
}

TEST(PluginLoader, MissingFile) {
  const std::string text = refusal("never_built");
  expect_one_line_naming(text, test_plugin("never_built"));
  EXPECT_NE(text.find("no such file"), std::string::npos) << text;
}

TEST(PluginLoader, NoEntryPoint) {
  const std::string text = refusal("no_entry");
  expect_one_line_naming(text, test_plugin("no_entry"));
  EXPECT_NE(text.find("no entry point 'wbi_plugin_entry'"), std::string::npos) << text;
  EXPECT_NE(text.find("WBI_PLUGIN"), std::string::npos) << text;
}

TEST(PluginLoader, OtherVersionNamesBoth) {
  const std::string text = refusal("other_version");
  expect_one_line_naming(text, test_plugin("other_version"));
  EXPECT_NE(text.find("built against wbi 0.0.9, this program is wbi " WBI_VERSION_STRING),
            std::string::npos)
      << text;
}

TEST(PluginLoader, OtherAbiNamesBoth) {
  const std::string text = refusal("other_abi");
  expect_one_line_naming(text, test_plugin("other_abi"));
  EXPECT_NE(text.find("eigen-align 64"), std::string::npos) << text;
  EXPECT_NE(text.find(WBI_PLUGIN_ABI), std::string::npos) << text;
}

TEST(PluginLoader, TypeRegisteredTwiceNamesBothProviders) {
  const std::string text = refusal("duplicate");
  expect_one_line_naming(text, test_plugin("duplicate"));
  EXPECT_NE(text.find("component type 'estimator' is registered twice"), std::string::npos) << text;
  EXPECT_NE(text.find("libwbi_builtin.so and by " + test_plugin("duplicate").string()),
            std::string::npos)
      << text;
}

TEST(PluginLoader, RegistrationThatThrows) {
  const std::string text = refusal("throwing");
  expect_one_line_naming(text, test_plugin("throwing"));
  EXPECT_NE(text.find("its registration failed: the lab's calibration file is missing"),
            std::string::npos)
      << text;
}

TEST(PluginLoader, UnresolvedSymbolCannotBeOpened) {
  const std::string text = refusal("unresolved");
  expect_one_line_naming(text, test_plugin("unresolved"));
  EXPECT_NE(text.find("cannot be opened"), std::string::npos) << text;
  EXPECT_NE(text.find("wbi_test_symbol_nobody_defines"), std::string::npos) << text;
}

}  // namespace
