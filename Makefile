# endosim: the haptic heart of a flexible-endoscopy simulator.
#
# The object lists below are the architecture: which module goes into which
# program. See docs/ARCHITECTURE.md for the threads and the data flow.
#
#   make            build build/endosimd, build/endoctl and build/endoview
#   make test       install missing Debian packages (as root), build with
#                   gcc and clang (-Werror), run every test
#   make demo       run the daemon on the simulated rig with the demo scenario
#                   and the viewer beside it (headless: a screenshot)
#   make bench      the figures: loop latency next to cyclictest's, the
#                   colon model, the haptic step, the drives, the viewer
#   make emulators  the drive emulators (tests/emulators/) and the drive
#                   benchmark program (run tests/bench/drives.sh)
#   make install    PREFIX=/usr/local DESTDIR= : binaries, config, systemd
#   make deps       install (as root) or name the Debian packages needed

VERSION := 0.1.0
CC ?= cc
BUILD ?= build
PREFIX ?= /usr/local
SYSCONFDIR ?= /etc
DESTDIR ?=
BINDIR = $(PREFIX)/bin
SBINDIR = $(PREFIX)/sbin
DATADIR = $(PREFIX)/share/endosim
DOCDIR = $(PREFIX)/share/doc/endosim
SYSTEMDDIR = $(PREFIX)/lib/systemd/system
SYSUSERSDIR = $(PREFIX)/lib/sysusers.d
TMPFILESDIR = $(PREFIX)/lib/tmpfiles.d
# udev does not read /usr/local: rules go where the administrator's go
UDEVDIR = $(SYSCONFDIR)/udev/rules.d

CFLAGS ?= -O2 -g
WARNINGS = -Wall -Wextra -Werror -Wshadow -Wpointer-arith -Wformat=2 \
	   -Wno-format-nonliteral
PKGS = libprotobuf-c inih libsystemd libusb-1.0 libmodbus
CLIENT_PKGS = libprotobuf-c
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
CASEDIR = $(DATADIR)/cases
ALL_CFLAGS = -std=c11 -D_GNU_SOURCE $(WARNINGS) $(CFLAGS) -I$(BUILD)/gen \
	     -DCONFIG_CASE_DIR='"$(CASEDIR)"' \
	     -Iproto $(PKG_CFLAGS) -MMD -MP
LDLIBS = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lpthread -lm
CLIENT_LDLIBS = $(shell pkg-config --libs $(CLIENT_PKGS) 2>/dev/null) -lm

# --- Debian packages -------------------------------------------------------
DEPS_BUILD = gcc make pkg-config protobuf-c-compiler libprotobuf-c-dev \
	     libinih-dev libsystemd-dev libusb-1.0-0-dev libmodbus-dev \
	     libglfw3-dev libepoxy-dev libcglm-dev libstb-dev \
	     fonts-dejavu-core
# libFuzzer's runtime is only a recommendation of clang: named here
DEPS_TEST = $(DEPS_BUILD) clang libclang-rt-14-dev libcmocka-dev socat jq \
	    procps systemd valgrind umockdev libumockdev-dev libglib2.0-dev \
	    $(DEPS_SCREEN) xdotool chromium
DEPS_BENCH = $(DEPS_BUILD) rt-tests jq umockdev libumockdev-dev \
	     libglib2.0-dev clang libclang-rt-14-dev $(DEPS_SCREEN)
# a screen for the viewer where there is none (tests, bench, headless demo)
DEPS_SCREEN = xvfb xauth libgl1-mesa-dri

# Installs the missing packages of $(1) as root; otherwise names them.
define ensure_packages
	@missing=""; for p in $(1); do \
		dpkg-query -W -f='$${Status}' $$p 2>/dev/null | \
			grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
		if [ "$$(id -u)" = 0 ]; then \
			echo "installing:$$missing"; \
			apt-get update && DEBIAN_FRONTEND=noninteractive \
				apt-get install -y --no-install-recommends $$missing; \
		else \
			echo "missing Debian packages; run as root:"; \
			echo "  apt-get update && apt-get install -y$$missing"; \
			exit 1; \
		fi; \
	fi
endef

# --- what goes where -------------------------------------------------------
PROTO_GEN = $(BUILD)/gen/endosim.pb-c.c $(BUILD)/gen/endosim.pb-c.h

# the wire: protocol, framing, client library, shared-memory reader
PROTO_OBJS = endosim.pb-c.o frame.o client.o names.o shm_reader.o \
	     session_file.o

# the colon and the endoscope: case files, centreline, mesh, OBJ, the
# model that ties them, the scope's kinematics
COLON_OBJS = anatomy.o centreline.o mesh.o objio.o colon.o scope.o contact.o

# endosimd: main, configuration, logging, the force loop and what it calls
# (rig backends, hand, haptics, safety with its fault words and the test
# commands' injections, publish, the colon and the scope), the control
# thread with the cases and the scene it serves, the recorder thread of
# training sessions with their directory and metrics
DAEMON_OBJS = main.o config.o regmap.o log.o loop.o rt.o histo.o spsc.o \
	      publish.o rig.o rig_sim.o plant.o hand.o scenario.o haptics.o \
	      safety.o faults.o inject.o godobject.o control.o cases.o \
	      scene.o recorder.o sessiontap.o sessiondir.o sessionpb.o \
	      metrics.o $(COLON_OBJS) $(DRIVE_OBJS)

# the drive layer: the rig of drives, one bus thread per bus, the drive
# interface and its backends (EPOS4 on USB, Modbus) with their protocols
DRIVE_OBJS = rig_drives.o bus.o drive.o drive_epos4.o epos4_frame.o \
	     canopen.o drive_modbus.o

# endoctl: the CLI over the sockets; what it makes of a session file (its
# metrics, again over the records of a file cut short, on the colon rebuilt
# from the file; CSV; the instructor's report)
ENDOCTL_OBJS = endoctl.o json.o inject.o sessiondir.o sessionpb.o \
	       sessionview.o metrics.o report.o $(COLON_OBJS)

# endoview: the viewer (viewer/). The link to the daemon (shared memory,
# the scene, commands and the hand) and the trainee's controls; the colon
# rebuilt with the daemon's own centreline and mesh, its levels of detail
# and the portal walk; the endoscopic view, the overview, the HUD; the
# replay of a session file, its colon built and served and its scope's
# tube made by the daemon's own modules (case, colon, scene, kinematics)
VIEWER_OBJS = endoview.o link.o rigctl.o ui.o input.o \
	      model.o lod.o portal.o \
	      gpumesh.o endo.o vessels.o overview.o shapes.o \
	      hud.o draw2d.o font.o gfx.o shot.o timing.o log.o \
	      replay.o state_text.o scene.o cases.o config.o regmap.o \
	      $(COLON_OBJS)
VIEWER_PKGS = glfw3 epoxy cglm stb inih
VIEWER_CFLAGS = $(shell pkg-config --cflags $(VIEWER_PKGS) 2>/dev/null)
VIEWER_LDLIBS = $(shell pkg-config --libs $(VIEWER_PKGS) $(CLIENT_PKGS) \
		  2>/dev/null) -lm

obj = $(addprefix $(BUILD)/obj/,$(1))

PROGRAMS = $(BUILD)/endosimd $(BUILD)/endoctl $(BUILD)/endoview

# --- unit tests (cmocka) and helpers --------------------------------------
UNIT_TESTS = test_config test_frame test_seqlock test_plant test_scenario \
	     test_safety test_epos4_frame test_canopen test_regmap \
	     test_config_drives test_colon test_scope test_scene \
	     test_godobject test_haptics test_session_file \
	     test_model test_lod test_portal test_input test_timing \
	     test_vessels test_metrics test_report test_course
test_config_OBJS = config.o regmap.o log.o names.o
test_session_file_OBJS = session_file.o
test_metrics_OBJS = metrics.o $(COLON_OBJS)
test_report_OBJS = report.o metrics.o names.o session_file.o $(COLON_OBJS)
test_frame_OBJS = frame.o endosim.pb-c.o
test_seqlock_OBJS = publish.o shm_reader.o log.o
test_plant_OBJS = plant.o
test_scenario_OBJS = scenario.o names.o
test_safety_OBJS = safety.o inject.o config.o regmap.o log.o names.o
test_epos4_frame_OBJS = epos4_frame.o
test_canopen_OBJS = canopen.o
test_regmap_OBJS = regmap.o
test_config_drives_OBJS = config.o regmap.o log.o names.o drive.o histo.o
test_colon_OBJS = $(COLON_OBJS)
test_godobject_OBJS = $(COLON_OBJS) godobject.o
test_haptics_OBJS = $(COLON_OBJS) godobject.o haptics.o plant.o config.o \
		    regmap.o log.o names.o
test_scope_OBJS = $(COLON_OBJS)
test_scene_OBJS = scene.o cases.o config.o regmap.o log.o names.o \
		  endosim.pb-c.o $(COLON_OBJS)
# the viewer's modules that need no window
VIEWER_SCENE_OBJS = scene.o cases.o config.o regmap.o log.o names.o \
		    endosim.pb-c.o $(COLON_OBJS)
test_model_OBJS = model.o $(VIEWER_SCENE_OBJS)
test_lod_OBJS = lod.o model.o $(VIEWER_SCENE_OBJS)
test_portal_OBJS = portal.o lod.o model.o $(VIEWER_SCENE_OBJS)
test_input_OBJS = input.o
test_timing_OBJS = timing.o
test_vessels_OBJS = vessels.o
test_course_OBJS = $(OFFLINE_OBJS) cases.o metrics.o names.o
TEST_TOOLS = shm_probe shm_latency obj_import scenario_gen fault_watch \
	     notify_listen session_synth session_script session_report
fault_watch_OBJS =
notify_listen_OBJS =
shm_probe_OBJS =
shm_latency_OBJS = histo.o
obj_import_OBJS = $(COLON_OBJS)
scenario_gen_OBJS = $(COLON_OBJS) config.o regmap.o log.o
session_script_OBJS = $(COLON_OBJS) metrics.o
session_report_OBJS = $(COLON_OBJS) metrics.o report.o
# the force loop off line, in lockstep (tests/tools/offline.h): the loop's
# own cycle (safety, kinematics, haptics) on the simulated rig and hand
OFFLINE_OBJS = offline.o loop.o sessiontap.o safety.o inject.o publish.o \
	       rt.o histo.o spsc.o session_file.o $(COLON_OBJS) godobject.o \
	       haptics.o hand.o scenario.o rig_sim.o plant.o config.o \
	       regmap.o log.o
session_synth_OBJS = $(OFFLINE_OBJS) cases.o state_text.o
BENCH_TOOLS = bench_colon bench_haptics
bench_haptics_OBJS = $(OFFLINE_OBJS) names.o

# --- device emulators (tests/emulators/): what the system tests and the
# drive benchmark run the real drive backends against
EMULATORS = epos4-emu modbus-emu
EMU_PKGS = umockdev-1.0 glib-2.0
EMU_CFLAGS = $(shell pkg-config --cflags $(EMU_PKGS) 2>/dev/null)
EMU_LIBS = $(shell pkg-config --libs $(EMU_PKGS) 2>/dev/null)
epos4-emu_OBJS = epos4_emu.o emu.o epos4_frame.o canopen.o plant.o
modbus-emu_OBJS = modbus_emu.o emu.o config.o regmap.o log.o names.o plant.o
# the drive benchmark: endosimd's rig of drives without the force loop
DRIVES_BENCH_OBJS = drives_bench.o rig.o rig_sim.o plant.o hand.o scenario.o \
		    config.o regmap.o log.o names.o histo.o rt.o $(DRIVE_OBJS)

.PHONY: all test check bench bench-tools demo install clean deps deps-test \
	deps-bench deps-build deps-demo \
	unit-tests clang-build asan-build fuzz fuzz-build fuzz-targets \
	emulators

all: $(PROGRAMS)

$(BUILD)/gen/endosim.pb-c.c $(BUILD)/gen/endosim.pb-c.h &: proto/endosim.proto
	@mkdir -p $(BUILD)/gen
	protoc-c --proto_path=proto --c_out=$(BUILD)/gen $<

$(BUILD)/obj/endosim.pb-c.o: $(BUILD)/gen/endosim.pb-c.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(BUILD)/obj/%.o: proto/%.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(BUILD)/obj/%.o: daemon/%.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(BUILD)/endosimd: $(call obj,$(DAEMON_OBJS) $(PROTO_OBJS))
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(LDFLAGS) $(LDLIBS)

$(BUILD)/endoctl: $(call obj,$(ENDOCTL_OBJS) $(PROTO_OBJS))
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(LDFLAGS) $(CLIENT_LDLIBS)

$(BUILD)/obj/%.o: viewer/%.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Idaemon $(VIEWER_CFLAGS) -c -o $@ $<

$(BUILD)/endoview: $(call obj,$(VIEWER_OBJS) $(PROTO_OBJS))
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(LDFLAGS) $(VIEWER_LDLIBS)

# unit tests: each test file with the modules it exercises
define unit_test_rule
$(BUILD)/tests/$(1): tests/unit/$(1).c $(call obj,$($(1)_OBJS)) $(PROTO_GEN)
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) -Idaemon -Iviewer -Itests/tools -o $$@ $$< \
		$(call obj,$($(1)_OBJS)) $$(LDFLAGS) $$(LDLIBS) -lcmocka
endef
$(foreach t,$(UNIT_TESTS),$(eval $(call unit_test_rule,$(t))))

# test tools: separate processes the tests and benchmarks run; the
# modules they share
$(BUILD)/obj/%.o: tests/tools/%.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Idaemon -c -o $@ $<

define test_tool_rule
$(BUILD)/tests/$(1): tests/tools/$(1).c \
		$(call obj,$(sort $($(1)_OBJS) $(PROTO_OBJS)))
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) -Idaemon -Itests/tools -o $$@ $$< \
		$(call obj,$(sort $($(1)_OBJS) $(PROTO_OBJS))) $$(LDFLAGS) \
		$$(LDLIBS)
endef
$(foreach t,$(TEST_TOOLS),$(eval $(call test_tool_rule,$(t))))

unit-tests: $(addprefix $(BUILD)/tests/,$(UNIT_TESTS) $(TEST_TOOLS) \
	$(BENCH_TOOLS) png_stats)

# pixel statistics of the viewer's screenshots (stb_image)
$(BUILD)/tests/png_stats: tests/tools/png_stats.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(VIEWER_CFLAGS) -o $@ $< $(LDFLAGS) -lstb -lm

# benchmarks: programs that print figures (tests/bench/)
bench-tools: $(addprefix $(BUILD)/tests/,$(TEST_TOOLS) $(BENCH_TOOLS) \
	png_stats)

$(BUILD)/tests/bench_haptics: tests/bench/bench_haptics.c \
		$(call obj,$(bench_haptics_OBJS))
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Idaemon -Itests/tools -o $@ $< \
		$(call obj,$(bench_haptics_OBJS)) $(LDFLAGS) $(LDLIBS)

$(BUILD)/tests/bench_colon: tests/bench/bench_colon.c \
		$(call obj,$(COLON_OBJS))
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Idaemon -o $@ $< $(call obj,$(COLON_OBJS)) \
		$(LDFLAGS) $(LDLIBS)

$(BUILD)/obj/%.o: tests/emulators/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(EMU_CFLAGS) -c -o $@ $<

define emulator_rule
$(BUILD)/emulators/$(1): $(call obj,$($(1)_OBJS))
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) -o $$@ $$^ $$(LDFLAGS) $$(LDLIBS) $$(EMU_LIBS)
endef
$(foreach e,$(EMULATORS),$(eval $(call emulator_rule,$(e))))

$(BUILD)/obj/drives_bench.o: tests/bench/drives_bench.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(BUILD)/bench/drives-bench: $(call obj,$(DRIVES_BENCH_OBJS))
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(LDFLAGS) $(LDLIBS)

# the emulators, and the benchmark that runs the drive code against them
emulators: $(addprefix $(BUILD)/emulators/,$(EMULATORS)) \
	$(BUILD)/bench/drives-bench

# --- fuzz targets (libFuzzer, clang) --------------------------------------
FUZZ_TARGETS = fuzz_frame fuzz_config fuzz_scenario fuzz_anatomy fuzz_objio \
	       fuzz_epos4 fuzz_session
fuzz_frame_OBJS = frame.o endosim.pb-c.o config.o regmap.o log.o names.o
fuzz_config_OBJS = config.o regmap.o log.o names.o
fuzz_scenario_OBJS = scenario.o names.o
fuzz_anatomy_OBJS = $(COLON_OBJS)
fuzz_objio_OBJS = $(COLON_OBJS)
fuzz_epos4_OBJS = epos4_frame.o
fuzz_session_OBJS = session_file.o metrics.o $(COLON_OBJS)
# every UBSan report aborts the target (as in the ASan build): a fuzzer that
# only printed it would go on and pass
FUZZ_CFLAGS = -g -O1 -fsanitize=fuzzer-no-link,address,undefined \
	      -fno-sanitize-recover=all
FUZZ_SECONDS ?= 60

define fuzz_rule
$(BUILD)/$(1): tests/fuzz/$(1).c $(call obj,$($(1)_OBJS))
	$$(CC) $$(ALL_CFLAGS) -Idaemon -fsanitize=fuzzer,address,undefined \
		-fno-sanitize-recover=all -o $$@ $$< \
		$(call obj,$($(1)_OBJS)) $$(LDLIBS)
endef
$(foreach t,$(FUZZ_TARGETS),$(eval $(call fuzz_rule,$(t))))

fuzz-targets: $(addprefix $(BUILD)/,$(FUZZ_TARGETS))

fuzz-build:
	$(MAKE) --no-print-directory BUILD=$(BUILD)/fuzz CC=clang \
		CFLAGS="$(FUZZ_CFLAGS)" fuzz-targets

# each target for FUZZ_SECONDS from the corpus in tests/fuzz/NAME/
fuzz: deps-test
	$(MAKE) --no-print-directory fuzz-build
	FUZZ_SECONDS=$(FUZZ_SECONDS) tests/fuzz/run.sh $(BUILD)/fuzz

# --- the two commands --------------------------------------------------------
deps: deps-test deps-bench

deps-build:
	$(call ensure_packages,$(DEPS_BUILD))

deps-demo:
	$(call ensure_packages,$(DEPS_BUILD) $(DEPS_SCREEN))

deps-test:
	$(call ensure_packages,$(DEPS_TEST))

deps-bench:
	$(call ensure_packages,$(DEPS_BENCH))

test: deps-test
	$(MAKE) --no-print-directory check

# the clang build is a compile check: same sources, same -Werror
clang-build:
	$(MAKE) --no-print-directory BUILD=$(BUILD)/clang CC=clang all \
		unit-tests emulators

# AddressSanitizer and UndefinedBehaviorSanitizer: a build of its own in
# which tests/run.sh runs every suite again; any report fails the run
SAN_FLAGS = -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all \
	    -fno-omit-frame-pointer
asan-build:
	$(MAKE) --no-print-directory BUILD=$(BUILD)/asan CFLAGS="$(SAN_FLAGS)" \
		LDFLAGS="-fsanitize=address,undefined" all unit-tests emulators

check: all unit-tests emulators clang-build asan-build fuzz-build
	BUILD=$(BUILD) tests/run.sh

demo: deps-demo
	$(MAKE) --no-print-directory all
	BUILD=$(BUILD) tests/demo.sh

bench: deps-bench
	$(MAKE) --no-print-directory all bench-tools emulators fuzz-build
	BUILD=$(BUILD) tests/bench/run.sh

# --- install ----------------------------------------------------------------
install: all
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(SBINDIR) \
		$(DESTDIR)$(SYSCONFDIR)/endosim $(DESTDIR)$(DATADIR)/scenarios \
		$(DESTDIR)$(CASEDIR) \
		$(DESTDIR)$(DOCDIR) $(DESTDIR)$(UDEVDIR) \
		$(DESTDIR)$(SYSTEMDDIR) $(DESTDIR)$(SYSUSERSDIR) \
		$(DESTDIR)$(TMPFILESDIR)
	install -m 0755 $(BUILD)/endosimd $(DESTDIR)$(SBINDIR)/endosimd
	install -m 0755 $(BUILD)/endoctl $(DESTDIR)$(BINDIR)/endoctl
	install -m 0755 $(BUILD)/endoview $(DESTDIR)$(BINDIR)/endoview
	test -e $(DESTDIR)$(SYSCONFDIR)/endosim/endosimd.conf || \
		install -m 0644 config/endosimd.conf \
			$(DESTDIR)$(SYSCONFDIR)/endosim/endosimd.conf
	install -m 0644 config/scenarios/*.scn $(DESTDIR)$(DATADIR)/scenarios/
	install -m 0644 config/cases/*.case $(DESTDIR)$(CASEDIR)/
	install -m 0644 README.md $(DESTDIR)$(DOCDIR)/README.md
	sed -e 's|@SBINDIR@|$(SBINDIR)|g' -e 's|@DOCDIR@|$(DOCDIR)|g' \
		-e 's|@SYSCONFDIR@|$(SYSCONFDIR)|g' systemd/endosimd.service \
		> $(DESTDIR)$(SYSTEMDDIR)/endosimd.service
	install -m 0644 systemd/endosim.sysusers \
		$(DESTDIR)$(SYSUSERSDIR)/endosim.conf
	install -m 0644 systemd/endosim.tmpfiles \
		$(DESTDIR)$(TMPFILESDIR)/endosim.conf
	install -m 0644 systemd/70-endosim.rules $(DESTDIR)$(UDEVDIR)/

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD)/obj $(BUILD)/tests -name '*.d' 2>/dev/null)
