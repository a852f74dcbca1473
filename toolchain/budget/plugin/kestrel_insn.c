/* kestrel_insn: a QEMU TCG plugin that counts executed guest instructions.
 *
 * Debian's qemu-user 7.2 can load plugins (-plugin) but ships neither plugins nor the
 * qemu-plugin.h header, so the few entry points used here are declared from the documented
 * plugin API of QEMU 7.2 (API version 1). At translation time each translation block (TB)
 * gets an inline "add its instruction count to a 64-bit counter" operation, which QEMU emits
 * as two host instructions in the TB's prologue: no helper call per instruction, so counting
 * costs little. A TB left early (a guest fault in the middle of it) is still counted whole;
 * for a benchmark that does not fault this is exact.
 *
 * Arguments (after the plugin path, comma separated): outfile=PATH writes the count there
 * ("insns N\n"); without it the count goes to QEMU's log through qemu_plugin_outs (visible
 * with `-d plugin`). The counter is not atomic: the count is exact for single-threaded
 * guests, which is how kestrel-bench runs its benchmarks.
 */
#include <inttypes.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define KESTREL_PLUGIN_EXPORT __attribute__((visibility("default")))

typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
struct qemu_info_t; /* only passed through, never read */
enum qemu_plugin_op { KESTREL_QEMU_PLUGIN_INLINE_ADD_U64 = 0 };
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb* tb);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void* userdata);

/* Provided by the qemu-arm executable that loads this library. */
extern void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id,
                                                  qemu_plugin_vcpu_tb_trans_cb_t cb);
extern size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb* tb);
extern void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb* tb,
                                                     enum qemu_plugin_op op, void* ptr,
                                                     uint64_t imm);
extern void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb,
                                           void* userdata);
extern void qemu_plugin_outs(const char* string);

/* QEMU refuses a plugin whose API version it does not know; 7.2 speaks version 1. */
KESTREL_PLUGIN_EXPORT int qemu_plugin_version = 1;

static uint64_t insn_count;
static char out_path[4096];

static void on_tb_translate(qemu_plugin_id_t id, struct qemu_plugin_tb* tb) {
  (void)id;
  qemu_plugin_register_vcpu_tb_exec_inline(tb, KESTREL_QEMU_PLUGIN_INLINE_ADD_U64, &insn_count,
                                           qemu_plugin_tb_n_insns(tb));
}

static void on_exit(qemu_plugin_id_t id, void* userdata) {
  (void)id;
  (void)userdata;
  char line[64];
  snprintf(line, sizeof line, "insns %" PRIu64 "\n", insn_count);
  if (out_path[0] != '\0') {
    FILE* f = fopen(out_path, "w");
    if (f != NULL) {
      fputs(line, f);
      fclose(f);
      return;
    }
  }
  qemu_plugin_outs(line);
}

KESTREL_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const struct qemu_info_t* info,
                                              int argc, char** argv) {
  (void)info;
  for (int i = 0; i < argc; ++i) {
    static const char key[] = "outfile=";
    if (strncmp(argv[i], key, sizeof key - 1) == 0) {
      const char* path = argv[i] + sizeof key - 1;
      if (strlen(path) >= sizeof out_path) return -1;
      strcpy(out_path, path);
    } else {
      fprintf(stderr, "kestrel_insn: unknown plugin argument '%s'\n", argv[i]);
      return -1;
    }
  }
  qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_translate);
  qemu_plugin_register_atexit_cb(id, on_exit, NULL);
  return 0;
}
