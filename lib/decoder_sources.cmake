# The decoder's source files, one list per library, relative to lib/. The native
# libraries (lib/coding, lib/coding/zerotree, lib/coding/codec.cmake) and the
# WebAssembly decoder (web/CMakeLists.txt) both take them from here, so the two
# decoders compile the same files. The Draco base-chunk reader is not listed: the
# native build adds coding/base_mesh_decoder.cpp (libdraco), the web build a JS
# bridge.
set(EQMESH_MESH_DECODER_SOURCES mesh/mesh.cpp mesh/semi_regular.cpp mesh/adaptive_level.cpp)
set(EQMESH_ENTROPY_SOURCES
  coding/entropy/byte_io.cpp
  coding/entropy/range_coder.cpp
  coding/entropy/quantizer_table.cpp)
set(EQMESH_EQ_DECODER_SOURCES
  coding/eq/eq_layout.cpp
  coding/eq/eq_model.cpp
  coding/eq/eq_decoder.cpp)
set(EQMESH_ZEROTREE_SOURCES
  coding/zerotree/edge_tree.cpp
  coding/zerotree/bit_io.cpp
  coding/zerotree/zerotree_coder.cpp)
set(EQMESH_STREAM_DECODER_SOURCES
  coding/atlas/atlas_layout.cpp
  coding/atlas/seam_split.cpp
  coding/compact_base/compact_base_model.cpp
  coding/compact_base/compact_base_decoder.cpp
  coding/compact_base/compact_positions.cpp
  coding/stream_header.cpp
  coding/crease_chunk.cpp
  coding/level_decoder.cpp
  coding/level_synthesis.cpp
  coding/zerotree_decoder.cpp
  coding/decoder.cpp
  coding/decoded_geometry.cpp)

# The list variable `name` with every entry prefixed by `dir`/.
function(eqmesh_sources_in dir name out)
  set(result "")
  foreach(file ${${name}})
    list(APPEND result "${dir}/${file}")
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()
