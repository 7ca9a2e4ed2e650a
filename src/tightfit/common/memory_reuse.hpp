#pragma once
/// The process keeps the memory it frees for its next allocations.
///
/// Every Newton step assembles Hessians and factorizes them in buffers of many
/// megabytes (triplets, sparse products, CHOLMOD's supernodes) that are freed at the
/// end of the step. With glibc's defaults such buffers are mapped and unmapped (or the
/// heap top trimmed) each time, and every page of the next step's buffer is a fresh
/// page fault: about 10 % of an optimization's time (perf, bench/optimization_bench).
/// Call once at start-up, before threads start.
namespace tightfit {

/// Raises glibc's mmap and trim thresholds (M_MMAP_THRESHOLD 256 MiB, M_TRIM_THRESHOLD
/// 1 GiB) so that freed buffers stay in the heap. Peak memory is unchanged (the freed
/// memory is reused, not added to); idle memory is returned only above 1 GiB.
void keep_freed_memory_for_reuse();

}  // namespace tightfit
