/* Tables shared across materials, in memory and on disk (table_cache.h). */
#include "subsurf/table_cache.h"

#include "subsurf/table_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct {
  int kind, fit;
  double eta, g;
  void *table; /* ss_table_radial or ss_table_gwc */
} entry;

struct ss_table_cache {
  char dir[4096];
  entry *entries;
  size_t count, capacity;
  ss_table_cache_stats stats;
};

void ss_table_cache_user_dir(char *buf, size_t size) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  if (xdg && xdg[0] == '/') {
    snprintf(buf, size, "%s/subsurf", xdg);
  } else if (home && home[0]) {
    snprintf(buf, size, "%s/.cache/subsurf", home);
  } else if (size) {
    buf[0] = '\0';
  }
}

/* mkdir -p */
static ss_status make_dirs(const char *dir, ss_error *err) {
  char path[4096];
  snprintf(path, sizeof path, "%s", dir);
  for (char *p = path + 1;; ++p) {
    int end = *p == '\0';
    if (*p == '/' || end) {
      *p = '\0';
      struct stat st;
      if (mkdir(path, 0777) != 0 && errno != EEXIST) {
        return ss_error_set(err, SS_ERR_IO, "table cache: cannot create '%s': %s", path,
                            strerror(errno));
      }
      if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        return ss_error_set(err, SS_ERR_IO, "table cache: '%s' is not a directory", path);
      }
      if (end) {
        return SS_OK;
      }
      *p = '/';
    }
  }
}

ss_status ss_table_cache_create(const char *dir, ss_table_cache **out, ss_error *err) {
  *out = NULL;
  if (dir && strlen(dir) >= sizeof((ss_table_cache *)0)->dir - 128) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "table cache: directory name too long");
  }
  if (dir && dir[0]) {
    ss_status st = make_dirs(dir, err);
    if (st != SS_OK) {
      return st;
    }
  }
  ss_table_cache *c = calloc(1, sizeof *c);
  if (!c) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table cache: out of memory");
  }
  snprintf(c->dir, sizeof c->dir, "%s", dir ? dir : "");
  *out = c;
  return SS_OK;
}

static void destroy_table(const entry *e) {
  if (e->kind == SS_TABLE_KIND_RADIAL) {
    ss_table_radial_destroy(e->table);
  } else {
    ss_table_gwc_destroy(e->table);
  }
}

void ss_table_cache_destroy(ss_table_cache *c) {
  if (!c) {
    return;
  }
  for (size_t i = 0; i < c->count; ++i) {
    destroy_table(&c->entries[i]);
  }
  free(c->entries);
  free(c);
}

void ss_table_cache_get_stats(const ss_table_cache *c, ss_table_cache_stats *stats) {
  *stats = c->stats;
}

/* %.17g keeps every bit of eta and g in the name; the header's exact values
 * are compared on load all the same. */
void ss_table_cache_path(const ss_table_cache *c, int kind, int fit, double eta, double g,
                         char *buf, size_t size) {
  if (!c->dir[0]) {
    snprintf(buf, size, "%s", "");
  } else if (kind == SS_TABLE_KIND_RADIAL) {
    snprintf(buf, size, "%s/table-radial_eta%.17g_g%.17g.sstab", c->dir, eta, g);
  } else {
    snprintf(buf, size, "%s/table-gwc-%s_eta%.17g_g%.17g.sstab", c->dir, ss_table_gwc_fit_name(fit),
             eta, g);
  }
}

static const entry *find(const ss_table_cache *c, int kind, int fit, double eta, double g) {
  for (size_t i = 0; i < c->count; ++i) {
    const entry *e = &c->entries[i];
    if (e->kind == kind && e->fit == fit && e->eta == eta && e->g == g) {
      return e;
    }
  }
  return NULL;
}

/* The disk file's table when it exists, passes the checks and has the key;
 * NULL otherwise (a refused file counts as rejected). */
static void *load(ss_table_cache *c, const char *path, int kind, int fit, double eta, double g) {
  struct stat st;
  if (!path[0] || stat(path, &st) != 0) {
    return NULL;
  }
  ss_error err;
  void *table = NULL;
  int match = 0;
  if (kind == SS_TABLE_KIND_RADIAL) {
    ss_table_radial *t;
    if (ss_table_radial_load(path, &t, &err) == SS_OK) {
      table = t;
      match = t->eta == eta && t->g == g;
    }
  } else {
    ss_table_gwc *t;
    if (ss_table_gwc_load(path, &t, &err) == SS_OK) {
      table = t;
      match = t->eta == eta && t->g == g && t->fit == fit;
    }
  }
  if (table && match) {
    c->stats.loads++;
    return table;
  }
  if (table) {
    entry e = {kind, fit, eta, g, table};
    destroy_table(&e);
  }
  c->stats.rejected++;
  return NULL;
}

static ss_status build(ss_table_cache *c, const char *path, int kind, int fit, double eta, double g,
                       void **table, ss_error *err) {
  ss_status st;
  ss_error werr;
  ss_status wst = SS_OK;
  if (kind == SS_TABLE_KIND_RADIAL) {
    ss_table_radial *t;
    st = ss_table_radial_build(eta, g, &t, err);
    *table = st == SS_OK ? t : NULL;
    if (st == SS_OK && path[0]) {
      wst = ss_table_radial_save(t, path, &werr);
    }
  } else {
    ss_table_gwc *t;
    st = ss_table_gwc_build(eta, g, fit, &t, err);
    *table = st == SS_OK ? t : NULL;
    if (st == SS_OK && path[0]) {
      wst = ss_table_gwc_save(t, path, &werr);
    }
  }
  if (st == SS_OK) {
    c->stats.builds++;
  }
  if (wst != SS_OK) {
    c->stats.write_failures++;
    snprintf(c->stats.last_failure, sizeof c->stats.last_failure, "%s", werr.message);
  }
  return st;
}

static ss_status get(ss_table_cache *c, int kind, int fit, double eta, double g, void **out,
                     ss_error *err) {
  const entry *e = find(c, kind, fit, eta, g);
  if (e) {
    c->stats.shared++;
    *out = e->table;
    return SS_OK;
  }
  if (c->count == c->capacity) {
    size_t n = c->capacity ? 2 * c->capacity : 4;
    entry *grown = realloc(c->entries, n * sizeof *grown);
    if (!grown) {
      return ss_error_set(err, SS_ERR_NO_MEMORY, "table cache: out of memory");
    }
    c->entries = grown;
    c->capacity = n;
  }
  char path[4096 + 128];
  ss_table_cache_path(c, kind, fit, eta, g, path, sizeof path);
  void *table = load(c, path, kind, fit, eta, g);
  if (!table) {
    ss_status st = build(c, path, kind, fit, eta, g, &table, err);
    if (st != SS_OK) {
      return st;
    }
  }
  c->entries[c->count++] = (entry){kind, fit, eta, g, table};
  *out = table;
  return SS_OK;
}

ss_status ss_table_cache_radial(ss_table_cache *c, double eta, double g,
                                const ss_table_radial **out, ss_error *err) {
  void *t = NULL;
  ss_status st = get(c, SS_TABLE_KIND_RADIAL, 0, eta, g, &t, err);
  *out = t;
  return st;
}

ss_status ss_table_cache_gwc(ss_table_cache *c, double eta, double g, int fit,
                             const ss_table_gwc **out, ss_error *err) {
  void *t = NULL;
  ss_status st = get(c, SS_TABLE_KIND_GWC, fit, eta, g, &t, err);
  *out = t;
  return st;
}
