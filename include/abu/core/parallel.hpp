// Independent work items on a few threads: items are taken in index order from a shared
// counter, so each item's result depends only on its index, never on the thread count. The
// first exception stops the hand-out of further items and is rethrown once every thread is
// done.
//
//   std::vector<double> out(n);
//   abu::for_each_index(n, threads, [&](int k) { out[k] = expensive(k); });
#pragma once

#include <functional>

namespace abu {

/// Calls body(k) for k = 0 .. count-1 on `threads` threads (0 or less: one per core; never more
/// than `count`), the caller's among them.
/// body returns false to stop the hand-out (an interruption); items already running finish.
void for_each_index(int count, int threads, const std::function<bool(int)>& body);

}  // namespace abu
