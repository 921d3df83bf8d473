# Header-only libraries, each compiled once. Debian ships spdlog and Asio as
# headers (spdlog's shared object aside, which a static binary cannot use);
# included as they are, each unit that logs or runs an event loop compiles
# their whole implementation again (spdlog alone: about 6 s of a unit's 9-15 s
# at -O3, in 48 units of the main tree and 17 of the fuzzing tree). So every
# user gets the libraries' "compiled separately" switch, and one unit each in
# cmake/compiled/ holds the implementation. spdlog's Debian build expects an
# external fmt, used header-only (it costs little per unit).
set(_acomms_compiled "${CMAKE_CURRENT_LIST_DIR}/compiled")
add_library(acomms_spdlog_compiled STATIC "${_acomms_compiled}/spdlog.cpp")
target_compile_definitions(acomms_spdlog_compiled PUBLIC
  FMT_HEADER_ONLY SPDLOG_FMT_EXTERNAL SPDLOG_COMPILED_LIB)
add_library(acomms::spdlog INTERFACE IMPORTED GLOBAL)
target_link_libraries(acomms::spdlog INTERFACE acomms_spdlog_compiled)
add_library(acomms_asio_compiled STATIC "${_acomms_compiled}/asio.cpp")
target_compile_definitions(acomms_asio_compiled PUBLIC
  ASIO_STANDALONE ASIO_NO_DEPRECATED ASIO_SEPARATE_COMPILATION)
target_link_libraries(acomms_asio_compiled PUBLIC Threads::Threads)
add_library(acomms::asio INTERFACE IMPORTED GLOBAL)
target_link_libraries(acomms::asio INTERFACE acomms_asio_compiled)
