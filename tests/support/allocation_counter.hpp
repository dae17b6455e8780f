// Counts the heap allocations of the test process: allocation_counter.cpp
// replaces the global operator new (in its own translation unit, so that the
// compiler does not pair the inlined replacement with std::free).
#pragma once

namespace wbi::test {

// Every thread's allocations: for code whose work runs on DDS threads too.
long allocation_count();
// The calling thread's allocations only: what a control tick itself allocates,
// whatever the DDS threads do meanwhile (heartbeats, acknowledgements).
long thread_allocation_count();

}  // namespace wbi::test
