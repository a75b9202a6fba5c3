# Builds Arduino sketches for an Uno the way the Arduino IDE does, with
# Debian's Arduino AVR core and avr-gcc: the board's own compile and link
# flags (platform.txt, boards.txt "uno"), the library's every .c/.cpp under
# src/ compiled with only src/ on its include path, each sketch's .ino turned
# into C++ by prepending #include <Arduino.h>.
#
#   make -f tests/embedded/arduino.mk OUT=build/arduino [SKETCHES="Basic ..."] [SKETCH_FLAGS=...]
#
# SKETCH_FLAGS go to the sketches' compile only (the tests pass
# -include tests/embedded/simavr_console.h).
# Gives $(OUT)/<Sketch>/<Sketch>.elf for each sketch. Departure from the IDE:
# cores/arduino/WString.cpp is left out (it does not compile with Debian's
# avr-gcc 5.4; no sketch here uses String), and the library and sketches are
# compiled with warnings on instead of -w: -Werror for the sketches and the
# Arduino wrapper, LIB_WARN (default -Wall -Wextra -Werror) for the C
# sources under src/.

ROOT := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/../..)
ARDUINO ?= /usr/share/arduino/hardware/arduino/avr
OUT ?= build/arduino
SKETCHES ?= $(notdir $(wildcard $(ROOT)/examples/arduino/*))

CC := avr-gcc
CXX := avr-g++
AR := avr-gcc-ar

BOARD := -mmcu=atmega328p -DF_CPU=16000000L -DARDUINO=10807 -DARDUINO_AVR_UNO -DARDUINO_ARCH_AVR
CFLAGS_IDE := -c -g -Os -std=gnu11 -ffunction-sections -fdata-sections -MMD -flto -fno-fat-lto-objects
CXXFLAGS_IDE := -c -g -Os -std=gnu++11 -fpermissive -fno-exceptions -ffunction-sections -fdata-sections \
  -fno-threadsafe-statics -Wno-error=narrowing -MMD -flto
SFLAGS_IDE := -c -g -x assembler-with-cpp -flto -MMD
LDFLAGS_IDE := -w -Os -g -flto -fuse-linker-plugin -Wl,--gc-sections
CORE_INC := -I$(ARDUINO)/cores/arduino -I$(ARDUINO)/variants/standard
OURS_WARN := -Wall -Wextra -Werror
LIB_WARN ?= -Wall -Wextra -Werror

CORE_DIR := $(ARDUINO)/cores/arduino
CORE_SRC := $(filter-out $(CORE_DIR)/WString.cpp, \
  $(wildcard $(CORE_DIR)/*.c $(CORE_DIR)/*.cpp $(CORE_DIR)/*.S))
CORE_OBJ := $(patsubst $(CORE_DIR)/%,$(OUT)/core/%.o,$(CORE_SRC))

LIB_SRC := $(shell cd $(ROOT)/src && find . -name '*.c' -o -name '*.cpp' | sed 's|^\./||' | sort)
LIB_OBJ := $(patsubst %,$(OUT)/lib/%.o,$(LIB_SRC))

ELVES := $(foreach s,$(SKETCHES),$(OUT)/$(s)/$(s).elf)

all: $(ELVES)

$(OUT)/core.a: $(CORE_OBJ)
	rm -f $@
	$(AR) rcs $@ $^

$(OUT)/core/%.c.o: $(CORE_DIR)/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_IDE) -w $(BOARD) $(CORE_INC) $< -o $@
$(OUT)/core/%.cpp.o: $(CORE_DIR)/%.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS_IDE) -w $(BOARD) $(CORE_INC) $< -o $@
$(OUT)/core/%.S.o: $(CORE_DIR)/%.S
	@mkdir -p $(dir $@)
	$(CC) $(SFLAGS_IDE) $(BOARD) $(CORE_INC) $< -o $@

# The library, as the IDE builds it: src/ is its only include directory.
$(OUT)/lib/%.c.o: $(ROOT)/src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_IDE) $(LIB_WARN) $(BOARD) $(CORE_INC) -I$(ROOT)/src $< -o $@
$(OUT)/lib/%.cpp.o: $(ROOT)/src/%.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS_IDE) $(OURS_WARN) $(BOARD) $(CORE_INC) -I$(ROOT)/src $< -o $@

# A sketch: <Name>.ino becomes <Name>.ino.cpp with Arduino.h included first.
# SKETCHES may also name the test-only sketches under tests/embedded/sketches.
define to_cpp
@mkdir -p $(dir $@)
{ echo '#include <Arduino.h>'; echo '#line 1 "$(notdir $<)"'; cat $<; } > $@
endef
$(OUT)/%.ino.cpp: $(ROOT)/examples/arduino/%.ino
	$(to_cpp)
$(OUT)/%.ino.cpp: $(ROOT)/tests/embedded/sketches/%.ino
	$(to_cpp)
$(OUT)/%.ino.cpp.o: $(OUT)/%.ino.cpp
	$(CXX) $(CXXFLAGS_IDE) $(OURS_WARN) $(BOARD) $(CORE_INC) -I$(ROOT)/src \
	  -iquote $(ROOT)/examples/arduino/$(dir $*) $(SKETCH_FLAGS) $< -o $@

.SECONDEXPANSION:
$(OUT)/%.elf: $(OUT)/%.ino.cpp.o $(LIB_OBJ) $(OUT)/core.a
	$(CC) $(LDFLAGS_IDE) -mmcu=atmega328p -o $@ $(OUT)/$*.ino.cpp.o $(LIB_OBJ) $(OUT)/core.a -L$(OUT) -lm

-include $(shell find $(OUT) -name '*.d' 2>/dev/null)

.PHONY: all
.SECONDARY:
