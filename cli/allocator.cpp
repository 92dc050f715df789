// The program's allocator settings. Linked with jemalloc (CMake option SKINSPEC_JEMALLOC), which reads this string
// at start-up (jemalloc(3), "malloc_conf"): its memory on transparent huge pages, so that a command holding many
// results (a 64 x 64 sweep: 12,288 of them, ~16 MB in ~770,000 small allocations) takes one page fault per 2 MB
// instead of one per 4 KB. Measured in docs/PERFORMANCE.md ("The program's allocator").
#ifdef SKINSPEC_JEMALLOC
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,metadata_thp:always";
}
#endif
