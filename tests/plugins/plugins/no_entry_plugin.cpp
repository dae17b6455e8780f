// A shared library without wbi's entry point (a plugin that forgot WBI_PLUGIN).
extern "C" __attribute__((visibility("default"))) int wbi_test_not_a_plugin() { return 1; }
