// The owner of the tests' precompiled header (tests/CMakeLists.txt): a program with no test of
// its own, built only so that the header is compiled once with the tests' flags.
