// Standalone Asio compiled once for the whole build.
//
// Header-only Asio compiles its implementation (reactor, timers, sockets,
// error categories) into each of the ninety-odd units that include it. With
// ASIO_SEPARATE_COMPILATION (set on acomms::asio for every user) the headers
// only declare, and this one unit defines it all: Asio's documented way to
// compile it separately.
#ifndef ASIO_SEPARATE_COMPILATION
#error "build with ASIO_SEPARATE_COMPILATION (see cmake/StaticDeps.cmake)"
#endif

#include <asio/impl/src.hpp>
