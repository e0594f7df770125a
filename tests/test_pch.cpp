// The source of the test programs' precompiled header (Catch2 and the common standard headers, named
// in tests/CMakeLists.txt): CMake builds the header with this file's target, and every test reuses it.
