/* fc_api.h — FC_API marks the functions of libfluidcast's documented API (the
 * installed headers fluidcast.h, fc_frame.h, fc_settings.h, fc_error.h): the only symbols
 * libfluidcast.so exports. Everything else in the library is compiled with
 * -fvisibility=hidden (client/lib/CMakeLists.txt), so an internal function
 * cannot become ABI by accident nor clash with a program's own. docs/abi.md
 * says what may change under which version; tests/install checks that the
 * exported symbols and the functions declared here are the same set. */
#ifndef FC_API_H
#define FC_API_H

#if defined(__GNUC__) && __GNUC__ >= 4
#define FC_API __attribute__((visibility("default")))
#else
#define FC_API
#endif

#endif
