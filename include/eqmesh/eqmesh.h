/* eqmesh decoder, C API: an EXT_normal_mesh_compression stream (.eqm, or the
 * bytes of the extension's bufferView) in; float32 positions, unit normals,
 * TEXCOORD_0 (streams with an atlas) and uint32 indices out. Usable from C, C#,
 * Rust or Python through any FFI: plain structs, no callbacks, every allocation
 * returned to the caller freed by eqmesh_mesh_free / eqmesh_progressive_destroy.
 *
 * Safe on untrusted bytes: a malformed, truncated or hostile stream gives a
 * non-zero status and a message, never a crash, hang or unbounded allocation
 * (see lib/coding/decoder.h for the allocation bound).
 *
 * Status codes are eqmesh's (lib/core/status.h): 0 ok, 2 parse error, 3 invalid
 * argument, 5 corrupt stream, 6 unsupported version, 7 unsupported feature,
 * 8 resource limit, 9 internal. */
#ifndef EQMESH_EQMESH_H_
#define EQMESH_EQMESH_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct eqmesh_decode_options {
  int max_level;          /* finest level to decode; -1: all */
  uint64_t max_triangles; /* 0: no limit; else at most this many triangles, refined where the surface
                             needs them and closed without cracks (streams with an atlas: the finest
                             uniform level within it) */
  int threads;            /* worker threads, 0: all cores (the output does not depend on it) */
} eqmesh_decode_options;

typedef struct eqmesh_mesh {
  uint32_t vertex_count, triangle_count;
  float* positions; /* 3 per vertex */
  float* normals;   /* 3 per vertex, unit (ext_spec "Reconstruction of normals") */
  float* texcoords; /* 2 per vertex, TEXCOORD_0; NULL when the stream has no atlas */
  uint32_t* indices; /* 3 per triangle, counter-clockwise */
  int level;         /* the level decoded */
  int levels;        /* the stream's level count J */
} eqmesh_mesh;

/* Defaults: every level, no triangle limit, all cores. */
void eqmesh_decode_options_init(eqmesh_decode_options* options);

/* Decodes `size` bytes (a whole stream, or a prefix holding the chunks up to the
 * level wanted). On success returns 0 and fills *out (free it with
 * eqmesh_mesh_free); else returns a status code, leaves *out empty and writes a
 * message into error[error_size] (NUL-terminated, truncated to fit; error may be
 * NULL). options may be NULL (defaults). */
int eqmesh_decode(const uint8_t* data, size_t size, const eqmesh_decode_options* options, eqmesh_mesh* out,
                  char* error, size_t error_size);

/* Frees what eqmesh_decode or eqmesh_progressive_decode put in *mesh and zeroes it
 * (safe on a zeroed mesh). */
void eqmesh_mesh_free(eqmesh_mesh* mesh);

/* Progressive decoding: feed the stream's bytes as they arrive; after each feed,
 * eqmesh_progressive_level says the finest level whose bytes are all there (-1:
 * not yet the base), and eqmesh_progressive_decode decodes any level up to it. */
typedef struct eqmesh_progressive eqmesh_progressive;

eqmesh_progressive* eqmesh_progressive_create(const eqmesh_decode_options* options);
/* 0, or a status code when the bytes so far are not the start of a valid stream
 * (a header that fails its checks, more bytes than the stream holds). */
int eqmesh_progressive_feed(eqmesh_progressive* p, const uint8_t* data, size_t size, char* error,
                            size_t error_size);
int eqmesh_progressive_level(const eqmesh_progressive* p);
int eqmesh_progressive_decode(eqmesh_progressive* p, int level, eqmesh_mesh* out, char* error, size_t error_size);
void eqmesh_progressive_destroy(eqmesh_progressive* p);

#ifdef __cplusplus
}
#endif

#endif /* EQMESH_EQMESH_H_ */
