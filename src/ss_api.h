/* ss_api.h — the library boundary: what every installed header wraps its
 * declarations in.
 *
 *   #include "ss_api.h"
 *   #include "ss_error.h"        (includes of other headers stay outside)
 *
 *   SS_BEGIN_DECLS
 *   ... the module's types and functions ...
 *   SS_END_DECLS
 *
 * In C++ the pair opens and closes `extern "C" {`, so that a C++ program
 * links against the C library.  In both languages it pushes and pops GCC's
 * default symbol visibility: the library is compiled with -fvisibility=hidden
 * (the top meson.build), and a function whose declaration lies inside the
 * pair keeps default visibility where the library defines it, so that
 * libsubspectra.so exports exactly what its installed headers declare and
 * nothing else (internal headers do not use the pair; tests/install checks
 * the export list).  static inline functions in headers export nothing. */
#ifndef SS_API_H
#define SS_API_H

#if defined(__GNUC__)
#define SS_VISIBILITY_PUSH_ _Pragma("GCC visibility push(default)")
#define SS_VISIBILITY_POP_  _Pragma("GCC visibility pop")
#else
#define SS_VISIBILITY_PUSH_
#define SS_VISIBILITY_POP_
#endif

#ifdef __cplusplus
#define SS_BEGIN_DECLS                                                                   \
  extern "C" {                                                                           \
  SS_VISIBILITY_PUSH_
#define SS_END_DECLS                                                                     \
  SS_VISIBILITY_POP_                                                                     \
  }
#else
#define SS_BEGIN_DECLS SS_VISIBILITY_PUSH_
#define SS_END_DECLS   SS_VISIBILITY_POP_
#endif

#endif
