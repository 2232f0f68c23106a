# endosim: the haptic heart of a flexible-endoscopy simulator.
#
# The wings below are the architecture: which layer a module belongs to and
# which layers each program links. See docs/ARCHITECTURE.md for the picture,
# the threads and the data flow.
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
#   make pictures   after make test: the docs' pictures from the tests'
#                   screenshots (build/pictures) copied over docs/
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
PKGS = libprotobuf-c inih libsystemd libusb-1.0 libmodbus zlib sqlite3 libpq \
       libsodium
CLIENT_PKGS = libprotobuf-c zlib inih
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
CASEDIR = $(DATADIR)/cases
ALL_CFLAGS = -std=c11 -D_GNU_SOURCE $(WARNINGS) $(CFLAGS) -I$(BUILD)/gen \
	     -DCONFIG_CASE_DIR='"$(CASEDIR)"' \
	     $(WING_INCLUDES) $(PKG_CFLAGS) -MMD -MP
LDLIBS = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lpthread -lm
CLIENT_LDLIBS = $(shell pkg-config --libs $(CLIENT_PKGS) 2>/dev/null) -lm

# --- Debian packages -------------------------------------------------------
DEPS_BUILD = gcc make pkg-config protobuf-c-compiler libprotobuf-c-dev \
	     libinih-dev libsystemd-dev libusb-1.0-0-dev libmodbus-dev zlib1g-dev \
	     libsqlite3-dev libpq-dev libsodium-dev \
	     libglfw3-dev libepoxy-dev libcglm-dev libstb-dev libopenal-dev \
	     fonts-dejavu-core espeak-ng
# libFuzzer's runtime is only a recommendation of clang: named here
DEPS_TEST = $(DEPS_BUILD) clang libclang-rt-14-dev libcmocka-dev socat jq sqlite3 \
	    postgresql \
	    procps iproute2 systemd valgrind umockdev libumockdev-dev libglib2.0-dev \
	    $(DEPS_SCREEN) xdotool chromium sox
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

# --- what goes where: the wings ---------------------------------------------
# A wing is a folder and a static library. A program links its own objects
# and the wings it uses, in the order below: a wing uses only wings after it
# (docs/ARCHITECTURE.md has the picture; tests/layers.sh checks each wing's
# includes and each program's libraries against it). An include names its
# wing: "model/colon.h", "rig/rig.h", "proto/fields.h".
#
# endosimd's own (daemon/):
#   control  the control thread (daemon/control/): the sockets, the clients,
#            the master configuration; its handlers: replies, cases,
#            sessions, trainees, guided replay; the records, and the
#            thread that feeds a centre's
#   recorder the recorder of training sessions (daemon/recorder/)
#   loop     the force loop (daemon/loop/): its cycle, the mailboxes the
#            control thread posts to it through, the safety state machine
#            and the fault words, the test commands' injections,
#            publishing, the tap into the recorder's rings
#   rig      the hardware (daemon/rig/): the rig interface, the simulated rig
#            and hand, scenarios, guided replay's guidance, the rig of
#            drives, one bus thread per bus, the drive backends (EPOS4 on
#            USB, Modbus) and their protocols
# the shared libraries (lib/, proto/), which endoctl and endoview link too:
#   session  training sessions (lib/session/): metrics and their map on the
#            wire (livemap), the session directory and its index, a
#            session's inputs (one reader), what a session file says
#            (views, CSV, the report), courses and the trainee's page,
#            the rig's records (SQLite) and a centre's (PostgreSQL)
#   conf     the configuration (lib/conf/): every key once, its file, its
#            printing; the cases: the model as the configuration sets it
#   model    the colon and the endoscope (lib/model/): case files,
#            centreline, mesh, OBJ, the colon, contact, the scope's
#            kinematics, the god-object, the rod, the haptics, the axes'
#            plant, the tools through the channel (tool.c), the scene
#            served; it knows nothing of the configuration
#   base     logging, the clock, real time, histograms, rings, vectors,
#            JSON, text (lib/base/)
#   proto    the wire (proto/): protocol, framing, client library,
#            shared-memory reader, session files, names, the published
#            fields' tables (fields.c)
# and the tests' own:
#   offline  the force loop off line, in lockstep (tests/tools/offline.h):
#            the loop's own cycle on the simulated rig and hand, and the
#            scripted trainee
#   viewer   endoview's modules (viewer/): the link to the daemon (shared
#            memory, the scene, commands and the hand) and the trainee's
#            controls; the colon rebuilt with the model's centreline and
#            mesh, its levels of detail and the portal walk; the endoscopic
#            view, the overview, the HUD, the unseen-mucosa map; the replay
#            of a session file
WINGS = offline viewer control recorder loop rig session conf model base \
	proto
offline_SRCS = tests/tools/offline.c tests/tools/trainee.c
viewer_SRCS = $(filter-out viewer/endoview.c,$(wildcard viewer/*.c))
control_SRCS = $(wildcard daemon/control/*.c)
recorder_SRCS = $(wildcard daemon/recorder/*.c)
loop_SRCS = $(wildcard daemon/loop/*.c)
rig_SRCS = $(wildcard daemon/rig/*.c)
session_SRCS = $(wildcard lib/session/*.c)
conf_SRCS = $(wildcard lib/conf/*.c)
model_SRCS = $(wildcard lib/model/*.c)
base_SRCS = $(wildcard lib/base/*.c)
proto_SRCS = $(wildcard proto/*.c)
proto_EXTRA = $(BUILD)/obj/gen/proto/endosim.pb-c.o # the generated protocol
WING_INCLUDES = -I. -Ilib -Idaemon

obj = $(patsubst %.c,$(BUILD)/obj/%.o,$(1))
wings = $(foreach w,$(1),$(BUILD)/lib/lib$(w).a)
PROTO_GEN = $(BUILD)/gen/proto/endosim.pb-c.c $(BUILD)/gen/proto/endosim.pb-c.h

# the programs: their own sources, the wings they link, their libraries
PROGRAMS = endosimd endoctl endoview
endosimd_SRCS = daemon/main.c
endosimd_WINGS = control recorder loop rig session conf model base proto
endosimd_LDLIBS = $(LDLIBS)
# endoctl (endoctl/): the CLI over the sockets; what it makes of a session
# file (its metrics, on the colon rebuilt from the file; CSV; the
# instructor's report)
endoctl_SRCS = $(wildcard endoctl/*.c)
endoctl_WINGS = session conf model base proto
# and a centre's records, which it reads itself (libpq)
endoctl_LDLIBS = $(CLIENT_LDLIBS) $(shell pkg-config --libs libpq 2>/dev/null)
endoview_SRCS = viewer/endoview.c
endoview_WINGS = viewer session conf model base proto
endoview_LDLIBS = $(VIEWER_LDLIBS)
VIEWER_PKGS = glfw3 epoxy cglm stb inih openal
VIEWER_CFLAGS = $(shell pkg-config --cflags $(VIEWER_PKGS) 2>/dev/null)
VIEWER_LDLIBS = $(shell pkg-config --libs $(VIEWER_PKGS) $(CLIENT_PKGS) \
		  2>/dev/null) -lm
# the patient's voice (viewer/voice.h, sound.h): clips spoken by espeak-ng
# into $(BUILD)/voice/NAME.wav, endoview's beside it (installed in
# $(VOICEDIR)); each clip's espeak-ng options and text
VOICEDIR = $(DATADIR)/voice
VOICE_CLIPS = groan ow hurts stop cry
VOICE_groan = -v en+m3 -s 70 -p 20 -a 150 "haah... ohhh"
VOICE_ow = -v en+m3 -s 130 -p 60 -a 160 "ow!"
VOICE_hurts = -v en+m3 -s 140 -p 55 -a 160 "ah, that hurts!"
VOICE_stop = -v en+m3 -s 150 -p 70 -a 180 "please stop! please!"
VOICE_cry = -v en+m3 -s 100 -p 95 -a 200 "aaaaaah!"
VOICE_WAVS = $(patsubst %,$(BUILD)/voice/%.wav,$(VOICE_CLIPS))

# --- device emulators (tests/emulators/): what the system tests and the
# drive benchmark run the real drive backends against; the drive benchmark:
# endosimd's rig of drives without the force loop
EMULATORS = emulators/epos4-emu emulators/modbus-emu
EMU_PKGS = umockdev-1.0 glib-2.0
EMU_CFLAGS = $(shell pkg-config --cflags $(EMU_PKGS) 2>/dev/null)
EMU_LIBS = $(shell pkg-config --libs $(EMU_PKGS) 2>/dev/null)
emulators/epos4-emu_SRCS = tests/emulators/epos4_emu.c tests/emulators/emu.c
emulators/modbus-emu_SRCS = tests/emulators/modbus_emu.c \
			    tests/emulators/emu.c
bench/drives-bench_SRCS = tests/bench/drives_bench.c
$(foreach p,$(EMULATORS) bench/drives-bench,\
	$(eval $(p)_WINGS = rig conf model base proto)\
	$(eval $(p)_LDLIBS = $$(LDLIBS) $$(EMU_LIBS)))

# --- unit tests (cmocka), test tools, benchmarks, fuzz targets: each one
# file that links every wing it may need (the linker takes only the modules
# it uses)
UNIT_TESTS = test_config test_frame test_seqlock test_plant test_scenario \
	     test_safety test_epos4_frame test_canopen test_regmap \
	     test_config_drives test_colon test_scope test_scene \
	     test_godobject test_haptics test_session_file test_fields \
	     test_model test_lod test_portal test_input test_timing test_shapes \
	     test_vessels test_metrics test_report test_course test_rod \
	     test_flex test_lumen test_clinic test_rodcourse test_guide \
	     test_livemap test_separation test_coursefile test_records \
	     test_parse test_gas test_patient test_mailbox test_valves \
	     test_burstmark test_hand test_pain test_perforation test_grip \
	     test_voice test_wav test_tool test_tool_loop test_centre \
	     test_toolview test_lensfx test_accounts test_resection \
	     test_training test_login
TEST_TOOLS = shm_probe shm_latency obj_import scenario_gen fault_watch \
	     notify_listen session_synth session_script session_report \
	     session_shapes records_gen
BENCH_TOOLS = bench_colon bench_haptics bench_metrics bench_tool
FUZZ_TARGETS = fuzz_frame fuzz_config fuzz_scenario fuzz_anatomy fuzz_objio \
	       fuzz_epos4 fuzz_session fuzz_rod fuzz_course
TEST_WINGS = $(WINGS)
FUZZ_WINGS = session rig conf model base proto

.PHONY: all test check bench bench-tools demo install clean deps deps-test \
	pictures \
	deps-bench deps-build deps-demo \
	unit-tests clang-build asan-build fuzz fuzz-build fuzz-targets \
	emulators

all: $(addprefix $(BUILD)/,$(PROGRAMS)) $(VOICE_WAVS)

$(PROTO_GEN) &: proto/endosim.proto
	@mkdir -p $(BUILD)/gen
	protoc-c --proto_path=. --c_out=$(BUILD)/gen $<

# one compile rule: each source's object in its wing's folder under obj/,
# the generated protocol's in obj/gen/ (whether BUILD is relative or not)
$(BUILD)/obj/%.o: %.c $(PROTO_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<
$(BUILD)/obj/gen/%.o: $(BUILD)/gen/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<
$(BUILD)/obj/viewer/%.o: ALL_CFLAGS += $(VIEWER_CFLAGS) \
	-DENDOVIEW_VOICE_DIR='"$(VOICEDIR)"'
# a clip whose line changed is spoken again
$(BUILD)/voice/%.wav: Makefile
	@mkdir -p $(dir $@)
	espeak-ng -w $@ $(VOICE_$*)
$(BUILD)/obj/tests/emulators/%.o: ALL_CFLAGS += $(EMU_CFLAGS)
# the rod's solver runs in the force loop: -O3 vectorises its 3x3 and 6x6
# blocks (a third fewer instructions than -O2; rod_algebra.h's, inline in
# rod.c)
$(BUILD)/obj/lib/model/rod.o: ALL_CFLAGS += -O3

define wing_rule
$(BUILD)/lib/lib$(1).a: $(call obj,$($(1)_SRCS)) $($(1)_EXTRA)
	@mkdir -p $$(dir $$@)
	rm -f $$@ && $$(AR) rcs $$@ $$^
endef
$(foreach w,$(WINGS),$(eval $(call wing_rule,$(w))))

define program_rule
$(BUILD)/$(1): $(call obj,$($(1)_SRCS)) $(call wings,$($(1)_WINGS))
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) -o $$@ $$^ $$(LDFLAGS) $$($(1)_LDLIBS)
endef
$(foreach p,$(PROGRAMS) $(EMULATORS) bench/drives-bench,\
	$(eval $(call program_rule,$(p))))

# a unit test, a test tool or a benchmark: one file and the wings
define test_rule
$(BUILD)/tests/$(1): $(2)/$(1).c $(call wings,$(TEST_WINGS)) $(PROTO_GEN)
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) -Itests/tools -o $$@ $$< \
		$(call wings,$(TEST_WINGS)) $$(LDFLAGS) $$(LDLIBS) $(3)
endef
$(foreach t,$(UNIT_TESTS),$(eval $(call test_rule,$(t),tests/unit,-lcmocka)))
$(foreach t,$(TEST_TOOLS),$(eval $(call test_rule,$(t),tests/tools)))
$(foreach t,$(BENCH_TOOLS),$(eval $(call test_rule,$(t),tests/bench)))

unit-tests: $(addprefix $(BUILD)/tests/,$(UNIT_TESTS) $(TEST_TOOLS) \
	$(BENCH_TOOLS) png_stats)

# pixel statistics of the viewer's screenshots (stb_image)
$(BUILD)/tests/png_stats: tests/tools/png_stats.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(VIEWER_CFLAGS) -o $@ $< $(LDFLAGS) -lstb -lm

# benchmarks: programs that print figures (tests/bench/), and the demo
# course's test and the scripted resection's, whose figures the bench shows
bench-tools: $(addprefix $(BUILD)/tests/,$(TEST_TOOLS) $(BENCH_TOOLS) \
	png_stats test_rodcourse test_resection)

# the emulators, and the benchmark that runs the drive code against them
emulators: $(addprefix $(BUILD)/,$(EMULATORS) bench/drives-bench)

# --- fuzz targets (libFuzzer, clang) --------------------------------------
# every UBSan report aborts the target (as in the ASan build): a fuzzer that
# only printed it would go on and pass
FUZZ_CFLAGS = -g -O1 -fsanitize=fuzzer-no-link,address,undefined \
	      -fno-sanitize-recover=all
FUZZ_SECONDS ?= 60

define fuzz_rule
$(BUILD)/$(1): tests/fuzz/$(1).c $(call wings,$(FUZZ_WINGS))
	$$(CC) $$(ALL_CFLAGS) -Itests/unit -fsanitize=fuzzer,address,undefined \
		-fno-sanitize-recover=all -o $$@ $$^ $$(LDLIBS)
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

# the docs' pictures: the screenshots the system tests kept in
# $(BUILD)/pictures (keep_picture, tests/common.sh), copied over docs/
# after `make test` (or after the tests that keep them); look at them first
pictures:
	@ls $(BUILD)/pictures/*.png >/dev/null 2>&1 || { echo \
		"no pictures in $(BUILD)/pictures: run make test first"; exit 1; }
	cp $(BUILD)/pictures/*.png docs/

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
		$(DESTDIR)$(CASEDIR) $(DESTDIR)$(DATADIR)/courses \
		$(DESTDIR)$(DOCDIR) $(DESTDIR)$(UDEVDIR) $(DESTDIR)$(VOICEDIR) \
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
	install -m 0644 config/courses/*.course $(DESTDIR)$(DATADIR)/courses/
	install -m 0644 config/centre-roles.sql $(DESTDIR)$(DATADIR)/
	install -m 0644 $(VOICE_WAVS) $(DESTDIR)$(VOICEDIR)/
	install -m 0644 README.md $(DESTDIR)$(DOCDIR)/README.md
	install -d $(DESTDIR)$(DOCDIR)/docs
	install -m 0644 docs/*.md docs/*.png $(DESTDIR)$(DOCDIR)/docs/
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
