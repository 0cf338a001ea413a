// The owner of the libraries' precompiled header (cmake/precompiled_headers.cmake): nothing of its
// own, compiled only so that the header is built once with the libraries' options.
