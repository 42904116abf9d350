/* OpenEXR through the Core C API (OpenEXR 3.1): one scanline part of 32-bit
 * float channels, ZIP compressed (16 lines per chunk). The library writes
 * through our write callback into the temporary file of an ss_atomic_file,
 * and reports errors through a callback instead of printing them.
 *
 * A reader takes a chunk whose stored size equals its raw size to be raw
 * (OpenEXR file layout). OpenEXR 3.1.5's ZIP encoder (Debian 12) keeps the
 * deflated bytes when they are exactly as long as the raw ones (reported
 * upstream as github.com/AcademySoftwareFoundation/openexr/issues/2306,
 * fixed there in 2026), so noisy images came back
 * with a 16-row band of garbage. The compress step is wrapped: such a chunk
 * is stored raw, as the file layout intends. */
#include "subsurf/image_io.h"

#include "core/atomic_file.h"
#include "io/image_io_internal.h"

#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* The Core API delivers messages through a callback on the thread that hit
 * the error; the most recent one is kept for our error record. */
static _Thread_local char exr_message[256];

static void exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  snprintf(exr_message, sizeof exr_message, "%s",
           msg && *msg ? msg : exr_get_default_error_message(code));
}

static ss_status exr_fail(ss_error *err, ss_status status, const char *verb, const char *path,
                          exr_result_t rv) {
  return ss_error_set(err, status, "cannot %s %s: %s", verb, path,
                      exr_message[0] ? exr_message : exr_get_default_error_message(rv));
}

typedef struct {
  ss_atomic_file *file;
  ss_error *err;
  ss_status status;
} exr_sink;

static int64_t exr_sink_write(exr_const_context_t ctxt, void *userdata, const void *buffer,
                              uint64_t size, uint64_t offset,
                              exr_stream_error_func_ptr_t error_cb) {
  exr_sink *sink = userdata;
  sink->status = ss_atomic_file_pwrite(sink->file, buffer, (size_t)size, offset, sink->err);
  if (sink->status != SS_OK) {
    error_cb(ctxt, EXR_ERR_WRITE_IO, "%s", sink->err ? sink->err->message : "write error");
    return -1;
  }
  return (int64_t)size;
}

typedef struct {
  exr_result_t (*compress)(exr_encode_pipeline_t *enc);
} exr_compressor;

static exr_result_t compress_or_store_raw(exr_encode_pipeline_t *enc) {
  const exr_compressor *inner = enc->encoding_user_data;
  exr_result_t rv = inner->compress(enc);
  if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes >= enc->packed_bytes) {
    /* The compressed buffer holds at least packed_bytes (the library sizes
     * it 10 % + 64 KiB above). */
    memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    enc->compressed_bytes = enc->packed_bytes;
  }
  return rv;
}

/* Channel names by channel count; the file lists them sorted (A B G R). */
static const char *channel_name(int channels, int c) {
  static const char *const rgba[4] = {"R", "G", "B", "A"};
  return channels == 1 ? "Y" : rgba[c];
}

static int channel_index(int channels, const char *name) {
  for (int c = 0; c < channels; ++c) {
    if (!strcmp(name, channel_name(channels, c))) {
      return c;
    }
  }
  return -1;
}

static exr_result_t write_chunks(exr_context_t ctx, const ss_image *img) {
  exr_compressor inner = {NULL};
  int32_t lines = 1;
  exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
  exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
  int started = 0;
  int nc = img->channels;
  size_t row = (size_t)img->width * (size_t)nc;
  for (int y = 0; rv == EXR_ERR_SUCCESS && y < img->height; y += lines) {
    exr_chunk_info_t cinfo;
    rv = exr_write_scanline_chunk_info(ctx, 0, y, &cinfo);
    if (rv != EXR_ERR_SUCCESS) {
      break;
    }
    rv = started ? exr_encoding_update(ctx, 0, &cinfo, &enc)
                 : exr_encoding_initialize(ctx, 0, &cinfo, &enc);
    if (rv != EXR_ERR_SUCCESS) {
      break;
    }
    for (int16_t c = 0; c < enc.channel_count; ++c) {
      exr_coding_channel_info_t *ch = &enc.channels[c];
      int k = channel_index(nc, ch->channel_name);
      ch->encode_from_ptr = (const uint8_t *)(img->data + (size_t)cinfo.start_y * row + k);
      ch->user_pixel_stride = (int32_t)(nc * sizeof(float));
      ch->user_line_stride = (int32_t)(row * sizeof(float));
      ch->user_data_type = EXR_PIXEL_FLOAT;
      ch->user_bytes_per_element = (int16_t)sizeof(float);
    }
    if (!started) {
      rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
      started = 1;
      if (rv != EXR_ERR_SUCCESS) {
        break;
      }
      if (enc.compress_fn) {
        inner.compress = enc.compress_fn;
        enc.encoding_user_data = &inner;
        enc.compress_fn = compress_or_store_raw;
      }
    }
    rv = exr_encoding_run(ctx, 0, &enc);
  }
  if (started) {
    exr_result_t drv = exr_encoding_destroy(ctx, &enc);
    rv = rv != EXR_ERR_SUCCESS ? rv : drv;
  }
  return rv;
}

ss_status ss_image_write_exr(const char *path, const ss_image *img, ss_error *err) {
  ss_status st = ss_image_io_check(path, img, err);
  if (st != SS_OK) {
    return st;
  }
  ss_atomic_file f;
  if ((st = ss_atomic_file_open(&f, path, SS_FILE_EXR, err)) != SS_OK) {
    return st;
  }
  exr_sink sink = {&f, err, SS_OK};
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = exr_error_handler;
  init.user_data = &sink;
  init.write_fn = exr_sink_write;
  exr_message[0] = '\0';
  exr_context_t ctx = NULL;
  int part = 0;
  exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == EXR_ERR_SUCCESS) {
    rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
  }
  if (rv == EXR_ERR_SUCCESS) {
    rv = exr_initialize_required_attr_simple(ctx, part, img->width, img->height,
                                             EXR_COMPRESSION_ZIP);
  }
  for (int c = 0; c < img->channels && rv == EXR_ERR_SUCCESS; ++c) {
    rv = exr_add_channel(ctx, part, channel_name(img->channels, c), EXR_PIXEL_FLOAT,
                         EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  }
  if (rv == EXR_ERR_SUCCESS) {
    rv = exr_write_header(ctx);
  }
  if (rv == EXR_ERR_SUCCESS) {
    rv = write_chunks(ctx, img);
  }
  if (ctx) {
    /* exr_finish writes the chunk offset table, so it can fail too. */
    exr_result_t frv = exr_finish(&ctx);
    rv = rv != EXR_ERR_SUCCESS ? rv : frv;
  }
  if (rv != EXR_ERR_SUCCESS) {
    ss_atomic_file_abort(&f);
    if (sink.status != SS_OK) {
      return sink.status;
    }
    return exr_fail(err, SS_ERR_IO, "write", path, rv);
  }
  return ss_atomic_file_commit(&f, err);
}

/* Maps the file's channels onto ours: R G B (+ A) or Y, or a lone channel of
 * any name. Returns the channel count, 0 when the layout is not one of these. */
static int map_channels(const exr_attr_chlist_t *chl, int *slot) {
  static const char *const names[5] = {"R", "G", "B", "A", "Y"};
  int found[5] = {-1, -1, -1, -1, -1};
  for (int i = 0; i < chl->num_channels; ++i) {
    slot[i] = -1;
    for (int k = 0; k < 5; ++k) {
      if (!strcmp(chl->entries[i].name.str, names[k])) {
        found[k] = i;
      }
    }
  }
  if (found[0] >= 0 && found[1] >= 0 && found[2] >= 0) {
    for (int k = 0; k < 3; ++k) {
      slot[found[k]] = k;
    }
    if (found[3] >= 0) {
      slot[found[3]] = 3;
      return 4;
    }
    return 3;
  }
  if (found[4] >= 0) {
    slot[found[4]] = 0;
    return 1;
  }
  if (chl->num_channels == 1) {
    slot[0] = 0;
    return 1;
  }
  return 0;
}

static exr_result_t read_chunks(exr_context_t ctx, const exr_attr_box2i_t *dw, const int *slot,
                                ss_image *img) {
  int32_t lines = 1;
  exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int started = 0;
  int nc = img->channels;
  size_t row = (size_t)img->width * (size_t)nc;
  for (int y = dw->min.y; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
    exr_chunk_info_t cinfo;
    rv = exr_read_scanline_chunk_info(ctx, 0, y, &cinfo);
    if (rv != EXR_ERR_SUCCESS) {
      break;
    }
    rv = started ? exr_decoding_update(ctx, 0, &cinfo, &dec)
                 : exr_decoding_initialize(ctx, 0, &cinfo, &dec);
    if (rv != EXR_ERR_SUCCESS) {
      break;
    }
    started = 1;
    /* Channel order in the pipeline is the file's (sorted) order, the same
     * order the slot table was built in. */
    for (int16_t c = 0; c < dec.channel_count; ++c) {
      exr_coding_channel_info_t *ch = &dec.channels[c];
      int k = slot[c];
      ch->decode_to_ptr =
          k < 0 ? NULL : (uint8_t *)(img->data + (size_t)(cinfo.start_y - dw->min.y) * row + k);
      ch->user_pixel_stride = (int32_t)(nc * sizeof(float));
      ch->user_line_stride = (int32_t)(row * sizeof(float));
      ch->user_data_type = EXR_PIXEL_FLOAT;
      ch->user_bytes_per_element = (int16_t)sizeof(float);
    }
    rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
    if (rv == EXR_ERR_SUCCESS) {
      rv = exr_decoding_run(ctx, 0, &dec);
    }
  }
  if (started) {
    exr_result_t drv = exr_decoding_destroy(ctx, &dec);
    rv = rv != EXR_ERR_SUCCESS ? rv : drv;
  }
  return rv;
}

ss_status ss_image_read_exr(const char *path, ss_image **out, ss_error *err) {
  *out = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = exr_error_handler;
  exr_message[0] = '\0';
  exr_context_t ctx = NULL;
  exr_result_t rv = exr_start_read(&ctx, path, &init);
  if (rv != EXR_ERR_SUCCESS) {
    ss_status st =
        exr_fail(err, rv == EXR_ERR_FILE_ACCESS ? SS_ERR_IO : SS_ERR_PARSE, "read", path, rv);
    exr_finish(&ctx);
    return st;
  }
  ss_status st = SS_OK;
  exr_storage_t storage;
  exr_attr_box2i_t dw;
  const exr_attr_chlist_t *chl = NULL;
  int slot[64];
  int channels = 0;
  ss_image *img = NULL;
  if ((rv = exr_get_storage(ctx, 0, &storage)) != EXR_ERR_SUCCESS ||
      (rv = exr_get_data_window(ctx, 0, &dw)) != EXR_ERR_SUCCESS ||
      (rv = exr_get_channels(ctx, 0, &chl)) != EXR_ERR_SUCCESS) {
    st = exr_fail(err, SS_ERR_PARSE, "read", path, rv);
  } else if (storage != EXR_STORAGE_SCANLINE) {
    st = ss_error_set(err, SS_ERR_UNSUPPORTED,
                      "cannot read %s: only scanline images are supported (not tiled or deep)",
                      path);
  } else if (chl->num_channels > 64 || (channels = map_channels(chl, slot)) == 0) {
    st = ss_error_set(err, SS_ERR_UNSUPPORTED,
                      "cannot read %s: expected channels R,G,B[,A] or Y (found %d channels)", path,
                      chl->num_channels);
  } else {
    for (int i = 0; i < chl->num_channels; ++i) {
      if (slot[i] >= 0 && (chl->entries[i].x_sampling != 1 || chl->entries[i].y_sampling != 1)) {
        st = ss_error_set(err, SS_ERR_UNSUPPORTED, "cannot read %s: subsampled channel %s", path,
                          chl->entries[i].name.str);
      }
    }
  }
  if (st == SS_OK) {
    img = ss_image_create(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, channels);
    if (!img) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "cannot read %s: out of memory", path);
    } else if ((rv = read_chunks(ctx, &dw, slot, img)) != EXR_ERR_SUCCESS) {
      st = exr_fail(err, SS_ERR_PARSE, "read", path, rv);
    }
  }
  exr_finish(&ctx);
  if (st != SS_OK) {
    ss_image_destroy(img);
    return st;
  }
  *out = img;
  return SS_OK;
}
