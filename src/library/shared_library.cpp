// shared_library.cpp: liblucent.so, the installed library (cmake/install_rules.cmake), is every object of the static
// libraries linked whole; this file only gives the shared library target a source of its own, as CMake requires.
// Nothing is defined here: the public API is declared in include/lucent/ and defined in the static libraries.
