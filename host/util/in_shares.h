// in_shares.h — work(first, last) over [0, n) on the host's threads, for items that write only
// their own results (so the outcome is the same bytes at any thread count and any schedule).
//
// The items go in chunks of at least minPerShare, about eight chunks per thread, which the threads
// take in turn as they finish the last: the guide's slots differ in cost by orders of magnitude
// and the costly ones sit together (split halves are appended at the end), so fixed equal shares
// left threads idle. At most one thread per hardware thread (16 at most); a small n runs on the
// calling thread alone and pays no thread start. An exception in a chunk reaches the caller (the
// lowest chunk's) after every thread has joined, so that an error becomes the command's one-line
// message rather than std::terminate.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace fen {

inline void inShares(std::size_t n, const std::function<void(std::size_t, std::size_t)>& work,
                     std::size_t minPerShare = 1)
{
    const std::size_t least = std::max<std::size_t>(minPerShare, 1);
    const std::size_t hw = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    const std::size_t threads = std::clamp<std::size_t>(n / least, 1, hw);
    if (threads == 1) {
        work(0, n);
        return;
    }
    const std::size_t chunk = std::max(least, (n + 8 * threads - 1) / (8 * threads));
    const std::size_t chunks = (n + chunk - 1) / chunk;
    std::atomic<std::size_t> next{0};
    std::vector<std::exception_ptr> failed(chunks);
    const auto run = [&] {
        for (std::size_t k; (k = next.fetch_add(1)) < chunks;) {
            try {
                work(k * chunk, std::min(n, (k + 1) * chunk));
            } catch (...) {
                failed[k] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t)
        pool.emplace_back(run);
    run();  // this thread takes chunks too
    for (std::thread& t : pool)
        t.join();
    for (const std::exception_ptr& e : failed)
        if (e)
            std::rethrow_exception(e);
}

}  // namespace fen
