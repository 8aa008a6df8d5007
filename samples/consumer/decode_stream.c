/* decode_stream FILE [MAX_TRIANGLES]: decodes an eqmesh stream (.eqm) with the C
 * API, first progressively (as a loader fed from the network would: a level as
 * soon as its bytes are in), then in one call within a triangle budget, and
 * prints what each gave. Exit status 0 on success. */
#include <stdio.h>
#include <stdlib.h>

#include <eqmesh/eqmesh.h>

static unsigned char* read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (f == NULL) return NULL;
  unsigned char* data = NULL;
  if (fseek(f, 0, SEEK_END) == 0) {
    const long n = ftell(f);
    if (n > 0 && fseek(f, 0, SEEK_SET) == 0 && (data = malloc((size_t)n)) != NULL) {
      *size = fread(data, 1, (size_t)n, f);
    }
  }
  fclose(f);
  return data;
}

static int decode_progressively(const unsigned char* data, size_t size) {
  char error[256];
  eqmesh_progressive* p = eqmesh_progressive_create(NULL);
  int shown = -1;
  for (size_t at = 0; at < size; at += 512) {
    const size_t n = size - at < 512 ? size - at : 512;
    if (eqmesh_progressive_feed(p, data + at, n, error, sizeof error) != 0) {
      fprintf(stderr, "feed: %s\n", error);
      eqmesh_progressive_destroy(p);
      return 1;
    }
    const int level = eqmesh_progressive_level(p);
    if (level <= shown) continue;
    eqmesh_mesh mesh;
    if (eqmesh_progressive_decode(p, level, &mesh, error, sizeof error) != 0) {
      fprintf(stderr, "level %d: %s\n", level, error);
      eqmesh_progressive_destroy(p);
      return 1;
    }
    printf("after %zu bytes: level %d of %d, %u vertices, %u triangles%s\n", at + n, mesh.level, mesh.levels,
           mesh.vertex_count, mesh.triangle_count, mesh.texcoords ? ", texcoords" : "");
    eqmesh_mesh_free(&mesh);
    shown = level;
  }
  eqmesh_progressive_destroy(p);
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: decode_stream FILE.eqm [MAX_TRIANGLES]\n");
    return 2;
  }
  size_t size = 0;
  unsigned char* data = read_file(argv[1], &size);
  if (data == NULL) {
    fprintf(stderr, "%s: cannot read\n", argv[1]);
    return 1;
  }
  int status = decode_progressively(data, size);
  eqmesh_decode_options options;
  eqmesh_decode_options_init(&options);
  if (argc > 2) options.max_triangles = strtoull(argv[2], NULL, 10);
  eqmesh_mesh mesh;
  char error[256];
  if (status == 0 && eqmesh_decode(data, size, &options, &mesh, error, sizeof error) != 0) {
    fprintf(stderr, "decode: %s\n", error);
    status = 1;
  } else if (status == 0) {
    printf("one call: level %d, %u vertices, %u triangles\n", mesh.level, mesh.vertex_count, mesh.triangle_count);
    eqmesh_mesh_free(&mesh);
  }
  free(data);
  return status;
}
