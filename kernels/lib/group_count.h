/* group_count.h — adding per-work-item counts to a global counter with one atomic per work-group.
 *
 * Why: on PoCL every work-item's atom_add on one shared counter makes the cores fight over its
 * cache line (measured: the emission ticket alone took 2.1 s of a 5 s render, ~130 ns a path).
 * Local atomics stay within one core; one global atomic per group of 64 is noise.
 * Every work-item of the group must call these (they contain barriers), so kernels compute their
 * result in a function with early returns and count at the end, never returning before it.
 */
#ifndef FEN_GROUP_COUNT_H
#define FEN_GROUP_COUNT_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

/* *counter += sum over the work-group of v. `scratch` is a kernel-scope local uint. */
static inline void group_count_add(volatile global ulong* counter, uint v, volatile local uint* scratch)
{
    if (get_local_id(0) == 0)
        *scratch = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (v != 0)
        atomic_add(scratch, v);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && *scratch != 0)
        atom_add(counter, (ulong)*scratch);
}

/* Tickets: each work-item with `want` set gets a distinct value of *counter (returned), with one
   global atomic per group. Which item gets which ticket varies with scheduling; the set of
   tickets handed out does not. */
static inline ulong group_ticket(volatile global ulong* counter, int want, volatile local uint* count,
                                 volatile local ulong* base)
{
    if (get_local_id(0) == 0)
        *count = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint mine = 0;
    if (want)
        mine = atomic_inc(count);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0)
        *base = *count != 0 ? atom_add(counter, (ulong)*count) : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    return *base + mine;
}

#endif /* FEN_GROUP_COUNT_H */
