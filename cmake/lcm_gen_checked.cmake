# Hardens the C++ decoders lcm-gen wrote into DIR (run as `cmake -DDIR=... -P lcm_gen_checked.cmake`).
#
# lcm-gen's decoders trust every length field: an array length of -1 or 2^31-1 makes
# `vector::resize` throw (or allocate gigabytes) before a byte of the array is read, and for
# lengths >= 2^29 (int32) / 2^28 (int64) the size check in lcm_coretypes.h overflows
# (`int total_size = sizeof(T) * elements`) so the decoder reads past the buffer; a string
# length of 0 or below makes `std::string::assign` throw. This script puts a bound on every
# length before it is used, so a hostile datagram makes decode() return -1, nothing else:
#   primitive array:  0 <= n and n * sizeof(element) <= bytes left
#   struct array:     0 <= n <= bytes left (every encoded struct takes at least one byte)
#   string:           1 <= length (with its NUL) <= bytes left
# It fails the build when lcm-gen's output has a length it does not recognise.
file(GLOB_RECURSE headers "${DIR}/*.hpp")
set(nl "\n")
foreach(h ${headers})
  file(READ "${h}" text)
  # Strings: the length includes the terminating NUL, so it is at least 1.
  string(REGEX REPLACE "if\\((__[A-Za-z0-9_]+) > maxlen - pos\\) return -1;"
         "if(\\1 < 1 || \\1 > maxlen - pos) return -1;" text "${text}")
  # Primitive arrays: resize followed by one __<type>_decode_array over the whole array.
  string(REGEX REPLACE
         "this->([A-Za-z0-9_]+(\\[a[0-9]+\\])*)\\.resize\\(this->([A-Za-z0-9_]+)\\);(${nl} *)tlen = (__[a-z0-9_]+_decode_array)\\("
         "if (this->\\3 < 0 || static_cast<long long>(this->\\3) * static_cast<long long>(sizeof(this->\\1[0])) > maxlen - pos) return -1;\\4this->\\1.resize(static_cast<size_t>(this->\\3));\\4tlen = \\5("
         text "${text}")
  # Arrays of structs, strings or arrays: one or more bytes per element.
  string(REGEX REPLACE
         "(${nl} *)this->([A-Za-z0-9_]+(\\[a[0-9]+\\])*)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
         "\\1if (this->\\4 < 0 || this->\\4 > maxlen - pos) return -1;\\1this->\\2.resize(static_cast<size_t>(this->\\4));"
         text "${text}")
  if(text MATCHES "\\.resize\\(this->" OR text MATCHES "if\\(__[A-Za-z0-9_]+ > maxlen")
    message(FATAL_ERROR "lcm_gen_checked: ${h} has a length field of a form this script does not bound; extend it")
  endif()
  file(WRITE "${h}" "${text}")
endforeach()
