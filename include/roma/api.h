/** @file
 * ROMA_API marks the functions a libroma shared library exports. The libraries are
 * compiled with hidden visibility, so nothing else (no internal function) is visible
 * to the program that links them. */
#ifndef ROMA_API_H
#define ROMA_API_H

#if defined(__GNUC__) || defined(__clang__)
/** Exports a public function from the shared library: default visibility with GCC and
 * Clang, nothing elsewhere. Callers never need it; static linking ignores it. */
#define ROMA_API __attribute__((visibility("default")))
#else
/** Elsewhere ROMA_API expands to nothing. */
#define ROMA_API
#endif

#endif /* ROMA_API_H */
