// in_shares.h — work(first, last) over [0, n) in contiguous shares, one thread each, for items that
// write only their own results (so the outcome is the same bytes at any thread count).
//
// At most one share per hardware thread (16 at most), and no share smaller than minPerShare items,
// so that a small n runs on the calling thread alone and pays no thread start. An exception in a
// share reaches the caller (the first share's in order) after every thread has joined, so that an
// error becomes the command's one-line message rather than std::terminate.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace fen {

inline void inShares(std::size_t n, const std::function<void(std::size_t, std::size_t)>& work,
                     std::size_t minPerShare = 1)
{
    const std::size_t hw = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    const std::size_t shares = std::clamp<std::size_t>(n / std::max<std::size_t>(minPerShare, 1), 1, hw);
    if (shares == 1) {
        work(0, n);
        return;
    }
    std::vector<std::exception_ptr> failed(shares);
    const auto share = [&](std::size_t t) {
        try {
            work(n * t / shares, n * (t + 1) / shares);
        } catch (...) {
            failed[t] = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < shares; ++t)
        pool.emplace_back(share, t);
    share(0);  // the first share on this thread
    for (std::thread& t : pool)
        t.join();
    for (const std::exception_ptr& e : failed)
        if (e)
            std::rethrow_exception(e);
}

}  // namespace fen
