#include "usart.h"
#include "clock.h"
int main(void){ clock_init(); usart1_init(9600); usart1_write((const uint8_t*)"hello\n",6);
 uint32_t t=clock_ms(); while(clock_ms()-t<500){} uint8_t b[8]; size_t n; 
 for(;;){ n=usart1_read(b,8); if(n){usart1_write(b,n); if(b[n-1]=='q') return 3;} if(clock_ms()-t>3000) return 4;} }
