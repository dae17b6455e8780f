// Counts the heap allocations of the test process: allocation_counter.cpp
// replaces the global operator new (in its own translation unit, so that the
// compiler does not pair the inlined replacement with std::free).
#pragma once

namespace wbi::test {

long allocation_count();

}  // namespace wbi::test
