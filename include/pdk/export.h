/* The mark of pdk's public API. libpdk is compiled with hidden symbol visibility
 * (-fvisibility=hidden): the shared library exports only the functions declared with PDK_EXPORT,
 * which are exactly the functions declared in include/pdk/ (test t089 checks both directions).
 * The library's internal functions (src/, kernels/) stay hidden: programs that call them link
 * the static library. */
#ifndef PDK_EXPORT_H
#define PDK_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define PDK_EXPORT __attribute__((visibility("default")))
#else
#define PDK_EXPORT
#endif

#endif
