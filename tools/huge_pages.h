// Transparent huge pages for the command's heap.
//
// Why: remeshing, encoding and the Metro meter fill hundreds of MB of fresh
// vectors and walk BVHs in random order. With 4 KiB pages a tenth of their time
// goes to page faults alone (perf, armadillo_50k remesh), and more to TLB misses.
// glibc 2.35+ backs malloc with transparent huge pages when GLIBC_TUNABLES holds
// glibc.malloc.hugetlb=1, but it reads tunables only when a process starts, so
// the command re-executes itself once with that set: remesh, encode and compare
// take 12-24 % less wall time, output bytes unchanged (measured on the bench VM,
// kernel THP mode "madvise": bench/log/2026-12-05-remesh-notebook.md).
#pragma once

namespace eqmesh::cli {

// Returns only when it does not re-execute: not Linux, EQMESH_HUGE_PAGES=0,
// GLIBC_TUNABLES already set (by the user, or by the re-execution itself), the
// kernel's THP mode is not "madvise" (with "always" malloc already gets huge
// pages, with "never" it cannot), a sanitizer or valgrind owns the allocator,
// or the exec fails (the command then runs as it is).
void ReexecWithHugePagesIfUseful(char** argv);

}  // namespace eqmesh::cli
