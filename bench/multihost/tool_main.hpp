// What the multi-host bench tools share: main() (`--help` prints the usage; a
// bad argument, std::invalid_argument from parse, exits 2 with the usage, any
// other error 1, each on one line naming the tool) and their argument parsing
// (every option takes a value: `--option value`).
#pragma once

#include <cstddef>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

namespace wbi::bench {

// Calls set(option, value) for each `--option value` pair of argv; set throws
// std::invalid_argument for an option it does not know.
template <class Set>
void for_each_option(int argc, char** argv, Set&& set) {
  for (int i = 1; i < argc; i += 2) {
    const std::string option = argv[i];
    if (i + 1 >= argc) {
      throw std::invalid_argument(option + ": missing value");
    }
    set(option, std::string(argv[i + 1]));
  }
}

// The whole of `text` as a number for which valid(number) holds, else an error
// naming the option and what it expected, e.g. "seconds > 0".
template <class Valid>
double number_option(const std::string& option, const std::string& text, const char* expected,
                     Valid&& valid) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !valid(value)) {
    throw std::invalid_argument(option + ": expected " + expected + ", got '" + text + "'");
  }
  return value;
}

template <class Options>
int tool_main(int argc, char** argv, const char* tool, const char* usage,
              Options (*parse)(int, char**), int (*run)(const Options&)) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::cout << usage;
    return 0;
  }
  try {
    return run(parse(argc, argv));
  } catch (const std::invalid_argument& error) {
    std::cerr << tool << ": " << error.what() << "\n" << usage;
    return 2;
  } catch (const std::exception& error) {
    std::cerr << tool << ": " << error.what() << "\n";
    return 1;
  }
}

}  // namespace wbi::bench
