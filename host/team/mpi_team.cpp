// mpi_team.cpp — MPI ranks as a team (mpi_team.h).
#include "team/mpi_team.h"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "util/error.h"

namespace fen {

namespace {

// The 128-bit sum over pairs of 64-bit words (util/fixed_point.h add128), as an MPI operation.
void add128Op(void* in, void* inout, int* len, MPI_Datatype*)
{
    const U128* a = static_cast<const U128*>(in);
    U128* b = static_cast<U128*>(inout);
    for (int i = 0; i < *len; ++i)
        b[i] = add128(a[i], b[i]);
}

void check(int rc, const char* what)
{
    if (rc != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING];
        int n = 0;
        MPI_Error_string(rc, text, &n);
        throw Error(cat("MPI: ", what, ": ", std::string(text, static_cast<std::size_t>(n))));
    }
}

class MpiTeam final : public Team {
public:
    MpiTeam(int* argc, char*** argv)
    {
        check(MPI_Init(argc, argv), "MPI_Init");
        // Errors come back as codes (check), so that they reach main()'s one-line message.
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
        MPI_Comm local;
        check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
              "MPI_Comm_split_type");
        MPI_Comm_rank(local, &localRank_);
        MPI_Comm_free(&local);
        static_assert(sizeof(U128) == 16, "U128 is two 64-bit words");
        check(MPI_Type_contiguous(2, MPI_UINT64_T, &u128_), "MPI_Type_contiguous");
        check(MPI_Type_commit(&u128_), "MPI_Type_commit");
        check(MPI_Op_create(&add128Op, 1, &add_), "MPI_Op_create");
        // the ticket counter: one word on rank 0, taken by atomic fetch-and-add (passive target,
        // so that rank 0 need not be in MPI for another rank to take a ticket)
        check(MPI_Win_allocate(rank_ == 0 ? 8 : 0, 8, MPI_INFO_NULL, MPI_COMM_WORLD, &counter_, &window_),
              "MPI_Win_allocate");
        if (rank_ == 0)
            *counter_ = 0;
        MPI_Barrier(MPI_COMM_WORLD);
    }
    ~MpiTeam() override
    {
        MPI_Win_free(&window_);
        MPI_Op_free(&add_);
        MPI_Type_free(&u128_);
        MPI_Finalize();
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int localRank() const override { return localRank_; }
    void sum(std::vector<U128>& v) override
    {
        // MPI counts are ints: a long vector goes in pieces
        constexpr std::size_t kPiece = std::size_t{1} << 26;
        for (std::size_t at = 0; at < v.size(); at += kPiece) {
            const int n = static_cast<int>(std::min(kPiece, v.size() - at));
            check(MPI_Allreduce(MPI_IN_PLACE, v.data() + at, n, u128_, add_, MPI_COMM_WORLD), "the 128-bit sum");
        }
    }
    void broadcast(std::string& bytes) override
    {
        unsigned long long n = bytes.size();
        check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "broadcast");
        bytes.resize(static_cast<std::size_t>(n));
        constexpr std::size_t kPiece = std::size_t{1} << 30;
        for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
            const int m = static_cast<int>(std::min<std::size_t>(kPiece, bytes.size() - at));
            check(MPI_Bcast(bytes.data() + at, m, MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
        }
    }
    std::vector<double> gather(double value) override
    {
        std::vector<double> all(static_cast<std::size_t>(size_));
        check(MPI_Allgather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, MPI_COMM_WORLD), "gather");
        return all;
    }
    std::vector<std::string> gatherToRoot(const std::string& text) override
    {
        const int n = static_cast<int>(std::min<std::size_t>(text.size(), std::size_t{1} << 30));
        std::vector<int> sizes(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
        check(MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "gather");
        std::string all;
        if (rank_ == 0) {
            long long total = 0;
            for (int k = 0; k < size_; ++k) {
                offsets[static_cast<std::size_t>(k)] = static_cast<int>(total);
                total += sizes[static_cast<std::size_t>(k)];
            }
            if (total > (1ll << 30))
                throw Error("MPI: the ranks' texts exceed 1 GiB together");
            all.resize(static_cast<std::size_t>(total));
        }
        check(MPI_Gatherv(text.data(), n, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, 0,
                          MPI_COMM_WORLD),
              "gather");
        std::vector<std::string> out;
        if (rank_ == 0)
            for (int k = 0; k < size_; ++k)
                out.push_back(all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(k)]),
                                         static_cast<std::size_t>(sizes[static_cast<std::size_t>(k)])));
        return out;
    }
    std::uint64_t ticket() override
    {
        std::uint64_t one = 1, got = 0;
        check(MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_), "ticket");
        check(MPI_Fetch_and_op(&one, &got, MPI_UINT64_T, 0, 0, MPI_SUM, window_), "ticket");
        check(MPI_Win_unlock(0, window_), "ticket");
        return got;
    }
    std::string describe() const override { return cat("MPI, ", size_, size_ == 1 ? " rank" : " ranks"); }

private:
    int rank_ = 0, size_ = 1, localRank_ = 0;
    MPI_Datatype u128_{};
    MPI_Op add_{};
    MPI_Win window_{};
    std::uint64_t* counter_ = nullptr;
};

}  // namespace

bool launchedByMpi()
{
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(v))
            return true;
    return false;
}

std::unique_ptr<Team> joinMpi(int* argc, char*** argv) { return std::make_unique<MpiTeam>(argc, argv); }

void abortMpi(int code)
{
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);
}

}  // namespace fen
