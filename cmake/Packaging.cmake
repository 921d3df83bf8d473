# The Debian package (CPack, DEB generator). In a configured and built tree:
#   cpack -G DEB            writes acommsd_<version>_<arch>.deb
# (tests/integration/package_test.sh builds one and checks its contents).
#
# What it holds, with CPACK_PACKAGING_INSTALL_PREFIX /usr:
#   /usr/bin/acommsd, /usr/bin/acommsctl     install rules in daemon/ and cli/
#   /usr/share/bash-completion/completions/acommsctl                  cli/
#   /usr/share/acommsd/proto/...             the public .proto files (below)
#   /lib/systemd/system/acommsd.service      packaging/acommsd.service
#   /etc/acommsd/acommsd.conf                packaging/acommsd.conf, a conffile
# and the maintainer scripts in packaging/debian/.
#
# The binaries find the .proto files at run time relative to themselves
# (<prefix>/bin/.. /share/acommsd/proto, see daemon/dccl/schema_loader.cpp), so the
# package needs no build of its own: ACOMMS_PROTO_DIR keeps pointing at the
# source tree, where the tests want it, and matters only for binaries run
# from the build tree.

set(_acomms_packaging "${CMAKE_SOURCE_DIR}/packaging")

# Every public .proto: the API and config schemas (for other gRPC clients)
# and the option extensions users' DCCL messages import.
install(DIRECTORY "${CMAKE_SOURCE_DIR}/api/proto/"
        DESTINATION share/acommsd/proto
        FILES_MATCHING PATTERN "*.proto")

# Absolute destinations: these paths are fixed by systemd and Debian, not
# by the install prefix.
install(FILES "${_acomms_packaging}/acommsd.service" DESTINATION /lib/systemd/system)
install(FILES "${_acomms_packaging}/acommsd.conf" DESTINATION /etc/acommsd)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME acommsd)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_CONTACT "acommsd maintainers <acommsd@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
# Wrapped by hand: dpkg shows the lines as they are.
set(CPACK_PACKAGE_DESCRIPTION [[
acommsd owns the acoustic modem link of an underwater vehicle, or of a
topside or buoy computer. Programs hand it messages over gRPC; it encodes
them as DCCL frames, keeps them in durable priority queues and sends them
in its TDMA slots. acommsctl is its command-line client.]])
# acommsd_0.1.0_amd64.deb, as Debian names packages.
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# dpkg-shlibdeps adds what the binaries link dynamically (the C library
# only: everything else is linked in); adduser is for the postinst.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
# Debian ships binaries stripped.
set(CPACK_STRIP_FILES ON)
# conffiles lists /etc/acommsd/acommsd.conf: CPack does not mark files
# under /etc by itself, and without it an upgrade would overwrite the
# operator's edits.
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  "${_acomms_packaging}/debian/conffiles"
  "${_acomms_packaging}/debian/postinst"
  "${_acomms_packaging}/debian/prerm"
  "${_acomms_packaging}/debian/postrm")
# Scripts 0755, conffiles 0644, whatever the checkout's modes.
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)

include(CPack)
