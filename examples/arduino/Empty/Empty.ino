void setup() { Serial.begin(9600); Serial.write("hi\n"); }
void loop() {}
