// The carrier of the test executables' precompiled header
// (tests/CMakeLists.txt): it compiles the header once; it is never run.
